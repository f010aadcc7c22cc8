// hitl campaign run FILE: a campaign's flights (docs/campaigns.md), each as a child process of this
// hitl (`--only INDEX`, the unit of work), N at a time; the progress on a terminal or JSON status
// lines; the results folder (per flight summary.json, result.json, flight.tlog, log.txt; the
// campaign's summary.json and junit.xml).
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <thread>

#include "cli/board_stack.h"
#include "cli/campaign_command.h"
#include "cli/campaign_history.h"
#include "cli/campaign_progress.h"
#include "cli/commands.h"
#include "cli/number_check.h"
#include "cli/parse_errors.h"
#include "cli/version.h"
#include "engine/campaign/campaign_file.h"
#include "engine/campaign/campaign_page.h"
#include "engine/campaign/campaign_run.h"
#include "engine/campaign/flight.h"
#include "engine/campaign/flight_run.h"
#include "engine/campaign/history.h"
#include "engine/campaign/results.h"
#include "engine/campaign/slurm.h"
#include "engine/campaign/work_units.h"
#include "engine/net/child_process.h"
#include "engine/faults/fault_spec.h"

namespace hitl::cli {

namespace {

struct CampaignRunOptions {
  std::string file;
  std::size_t jobs = 0;  ///< 0: the cores
  std::string out_dir;   ///< empty: campaign-<name>
  std::optional<std::size_t> only;
  bool resume = false;
  bool rerun_failed = false;
  std::string history;  ///< --history FILE (empty: the default, campaign::default_history_path())
  std::string label;    ///< --label TEXT
  bool no_history = false;
  std::string px4_dir;  ///< --px4 DIR: stack = "px4"'s build, over the file's px4 = "DIR"
};


std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

/// This hitl, for the children.
std::string self_path() {
  std::error_code ec;
  const auto p = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::string("hitl") : p.string();
}

int run_one(const GlobalOptions& g, const campaign::Campaign& c, const std::vector<campaign::Flight>& flights,
            const CampaignRunOptions& o, const std::string& out_dir) {
  if (*o.only >= flights.size())
    return log_error("campaign", Error::usage("--only " + std::to_string(*o.only) + ": the campaign has flights 0 to " +
                                              std::to_string(flights.size() - 1)));
  const auto& flight = flights[*o.only];
  FlightEvents events(g);
  EmulatedBoardStack board(events);
  campaign::Px4FlightStack px4(c);
  campaign::FlightStack& stack = c.stack == campaign::Stack::Px4 ? static_cast<campaign::FlightStack&>(px4) : board;
  bool stopped = false;
  log_info(g, "hitl campaign: flight " + std::to_string(flight.index) + " " + flight.name + " (id " + flight.id + ") into " +
                  campaign::flight_folder(out_dir, flight));
  auto r = campaign::run_flight(c, flight, stack, out_dir, stop_flag_on_signals(), events, stopped);
  if (stopped) {
    log_error("campaign", "flight " + flight.name + " stopped before its end; no result written");
    return kExitFailed;
  }
  if (!r) return log_error("campaign", r.error().prefixed("flight " + flight.name + ": "));
  if (g.json) {
    auto j = campaign::to_json(*r);
    j["type"] = "summary";
    print_json_line(j);
  } else {
    std::cout << r->outcome << ": " << r->summary_line << '\n';
    for (const auto& v : r->verdicts)
      if (!v.ok) std::cout << "  " << v.criterion << ": " << v.message << '\n';
  }
  return r->outcome == "passed" ? kExitOk : kExitFailed;
}

/// Where a campaign's results go and how this run is named: what run and collect both finish with.
struct Finish {
  std::string out_dir;
  std::string history;  ///< empty: kept out of the history
  std::string label;
  std::string started_utc;
  double wall_s = 0;
  bool stopped = false;
  bool collected = false;  ///< by collect: wall_s is the flights' own times added up
};

/// summary.json and junit.xml into the folder, the run into the history, the summary line (or
/// JSON); the exit code: 0 when every flight passed.
int finish_campaign(const GlobalOptions& g, const campaign::Campaign& c, const std::vector<campaign::Flight>& flights,
                    const std::vector<std::optional<campaign::FlightResult>>& results, const Finish& f) {
  if (auto ok = campaign::write_results(f.out_dir, c, flights, results, f.wall_s, f.stopped); !ok)
    return log_error("campaign", ok.error());
  const auto t = campaign::tally(results);
  bool history_failed = false;
  if (!f.history.empty()) {
    campaign::RunRecord record{f.label, f.started_utc, f.wall_s, f.stopped};
    if (auto ok = campaign::record_run(f.history, c, flights, results, record); !ok) {
      log_error("campaign", ok.error().prefixed("--history: "));
      history_failed = true;
    }
  }
  // The page last: it draws the history with this run in it.
  campaign::PageRun page{f.label, f.started_utc, kVersion, f.wall_s, f.stopped, f.collected};
  if (history_failed) page.no_history_reason = "this run could not be added to the history " + f.history;
  const auto page_started = std::chrono::steady_clock::now();
  const std::string page_path = (std::filesystem::path(f.out_dir) / campaign::kPageFile).string();
  const auto page_written = campaign::write_campaign_page(f.out_dir, c, flights, results, page, history_failed ? "" : f.history);
  if (!page_written) log_error("campaign", page_written.error());
  else {
    std::error_code ec;
    const auto bytes = std::filesystem::file_size(page_path, ec);
    char line[160];
    std::snprintf(line, sizeof line, "hitl campaign: %s: %.0f kB, written in %.0f ms", page_path.c_str(), ec ? 0.0 : bytes / 1e3,
                  std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - page_started).count());
    if (g.verbosity > 0) log_info(g, line);
  }
  if (g.json) {
    print_json_line(campaign::campaign_summary_json(c, flights, results, f.wall_s, f.stopped));
  } else {
    char line[256];
    std::snprintf(line, sizeof line, "campaign %s: %zu flights: %zu passed, %zu failed, %zu errors, %zu not flown; %.1f s", c.name.c_str(),
                  t.flights, t.passed, t.failed, t.errors, t.missing, f.wall_s);
    std::cout << line << (f.stopped ? " (stopped: --resume flies the rest)" : "") << '\n'
              << "results: " << f.out_dir << "/ (" << campaign::kCampaignSummaryFile << ", " << campaign::kJunitFile << ", "
              << campaign::kPageFile << ", flights/<id>/)\n";
    if (!f.history.empty() && !history_failed) std::cout << "history: " << f.history << " (hitl campaign history)\n";
    if (page_written) std::cout << "page: " << page_path << " (open it in a browser)\n";
  }
  return t.passed == t.flights && !history_failed && page_written ? kExitOk : kExitFailed;
}

/// The campaign file, read with the fault catalogue's "did you mean".
Expected<campaign::Campaign> load_campaign_file(const std::string& file) {
  const faults::Suggest suggest = [](const std::string& name) { return closest(name, faults::fault_names()).value_or(""); };
  return campaign::load_campaign(file, suggest);
}

/// The file, and for stack = "px4" its PX4 build found (`px4_dir`: --px4 DIR over the file's), so
/// that a bad DIR is refused before any flight starts.
Expected<campaign::Campaign> load_flown_campaign(const std::string& file, const std::string& px4_dir) {
  auto c = load_campaign_file(file);
  if (!c) return c;
  if (auto found = campaign::find_campaign_px4(*c, px4_dir); !found) return found.error();
  return c;
}

/// "the emulated board", "PX4 v1.16.0 SITL (DIR), a PX4 per flight".
std::string stack_words(const campaign::Campaign& c) {
  if (c.stack != campaign::Stack::Px4 || !c.px4 || !c.px4->build) return "the emulated board";
  const auto& b = *c.px4->build;
  return "PX4" + (b.version.empty() ? std::string() : " " + b.version) + " SITL (" + b.build_dir + "; one PX4 per flight)";
}

int run_campaign_command(const GlobalOptions& g, const CampaignRunOptions& o) {
  auto c = load_flown_campaign(o.file, o.px4_dir);
  if (!c) return log_error("campaign", c.error());
  const auto flights = campaign::expand(*c);
  const std::string out_dir = o.out_dir.empty() ? "campaign-" + c->name : o.out_dir;
  if (o.only) return run_one(g, *c, flights, o, out_dir);
  auto history = run_history(o.no_history, o.history);
  if (!history) return log_error("campaign", history.error());
  const std::string started_utc = utc_now();

  std::error_code ec;
  const std::string file_abs = std::filesystem::absolute(o.file, ec).string();
  const std::string out_abs = std::filesystem::absolute(out_dir, ec).string();
  campaign::RunOptions ro;
  ro.out_dir = out_dir;
  ro.jobs = o.jobs != 0 ? o.jobs : std::max(1u, std::thread::hardware_concurrency());
  ro.mode = o.rerun_failed ? campaign::RunMode::RerunFailed : o.resume ? campaign::RunMode::Resume : campaign::RunMode::Fresh;
  ro.program = self_path();
  const int verbosity = g.verbosity;
  const std::string px4_abs = o.px4_dir.empty() ? std::string() : std::filesystem::absolute(o.px4_dir, ec).string();
  ro.child_args = [file_abs, out_abs, verbosity, px4_abs](const campaign::Flight& f) {
    std::vector<std::string> args{"campaign", "run", file_abs, "--only", std::to_string(f.index), "--out", out_abs};
    if (!px4_abs.empty()) args.insert(args.end(), {"--px4", px4_abs});
    for (int i = 0; i < verbosity; ++i) args.push_back("-v");
    return args;
  };
  log_info(g, "hitl campaign: " + c->name + ": " + std::to_string(flights.size()) + " flights (" +
                  std::to_string(c->trajectories.size()) + " trajectories x " + std::to_string(c->fault_cases.size()) +
                  " fault cases x " + std::to_string(c->seeds.size()) + " seeds x " + std::to_string(c->speeds.size()) +
                  " speeds) against " + stack_words(*c) + ", " + std::to_string(ro.jobs) + " at a time, into " + out_dir +
                  " (Ctrl-C stops; --resume continues)");
  RunPrinter printer(g, c->name);
  auto outcome = campaign::run_campaign(*c, flights, ro, stop_flag_on_signals(), printer);
  printer.clear_line();
  if (!outcome) return log_error("campaign", outcome.error());
  return finish_campaign(g, *c, flights, outcome->results, {out_dir, *history, o.label, started_utc, outcome->wall_s, outcome->stopped});
}

struct CampaignCollectOptions {
  std::string file;
  std::string out_dir;
  std::string history;
  std::string label;
  bool no_history = false;
};

/// hitl campaign collect: the flights that ran elsewhere (`--only`, each into the shared folder)
/// gathered into the folder's summary.json and junit.xml, and one run of the history.
int run_collect_command(const GlobalOptions& g, const CampaignCollectOptions& o) {
  auto c = load_campaign_file(o.file);
  if (!c) return log_error("campaign", c.error());
  // PX4's version for the history, when this machine has the build the file names (the flights
  // ran elsewhere: without it the history names no version).
  if (c->stack == campaign::Stack::Px4) (void)campaign::find_campaign_px4(*c, "");
  const auto flights = campaign::expand(*c);
  const std::string out_dir = o.out_dir.empty() ? "campaign-" + c->name : o.out_dir;
  std::error_code ec;
  if (!std::filesystem::is_directory(std::filesystem::path(out_dir) / "flights", ec))
    return log_error("campaign", Error::input(out_dir + " has no flights/ folder: nothing to collect (hitl campaign run " + o.file +
                                              " --only INDEX --out " + out_dir + " writes one flight there)"));
  auto history = run_history(o.no_history, o.history);
  if (!history) return log_error("campaign", history.error());
  const auto results = campaign::read_results(out_dir, flights);
  double wall_s = 0;  // the flights' own wall times: they ran elsewhere, maybe at once
  for (const auto& r : results)
    if (r) wall_s += r->wall_s;
  log_info(g, "hitl campaign: " + c->name + ": collecting " + std::to_string(flights.size()) + " flights' results from " + out_dir);
  return finish_campaign(g, *c, flights, results, {out_dir, *history, o.label, utc_now(), wall_s, false, true});
}

struct CampaignMatrixOptions {
  std::string file;
  std::string output;  ///< -o FILE (empty: standard output)
};

struct CampaignK8sOptions {
  std::string file;
  std::string output;
  std::string image;
  std::string path_in_image;  ///< empty: FILE as given
  std::string claim = "hitl-results";
  std::size_t parallelism = 0;
};

/// `text` to -o FILE, or to standard output.
int write_output(const std::string& text, const std::string& output) {
  if (output.empty()) {
    std::cout << text << '\n';
    return kExitOk;
  }
  std::ofstream out(output);
  if (!(out << text << '\n'))
    return log_error("campaign", Error::unavailable("cannot write " + output + ": " + std::strerror(errno)));
  return kExitOk;
}

int run_matrix_command(const CampaignMatrixOptions& o) {
  auto c = load_campaign_file(o.file);
  if (!c) return log_error("campaign", c.error());
  auto matrix = campaign::ci_matrix(*c, campaign::expand(*c));
  if (!matrix) return log_error("campaign", matrix.error());
  return write_output(matrix->dump(), o.output);
}

int run_k8s_command(const CampaignK8sOptions& o) {
  auto c = load_campaign_file(o.file);
  if (!c) return log_error("campaign", c.error());
  campaign::IndexedJobOptions k;
  k.image = o.image;
  k.campaign_path = o.path_in_image.empty() ? o.file : o.path_in_image;
  k.results_claim = o.claim;
  k.parallelism = o.parallelism;
  return write_output(campaign::k8s_indexed_job(*c, campaign::expand(*c).size(), k).dump(2), o.output);
}

struct CampaignSlurmOptions {
  std::string file;
  std::string out_dir;
  std::string partition;
  std::size_t max_running = 0;
  std::string history;
  std::string label;
  bool no_history = false;
};

/// hitl campaign slurm: the flights as a Slurm job array and collect after it, submitted with sbatch.
int run_slurm_command(const GlobalOptions& g, const CampaignSlurmOptions& o) {
  auto c = load_flown_campaign(o.file, "");
  if (!c) return log_error("campaign", c.error());
  const auto sbatch = net::find_on_path("sbatch");
  if (!sbatch)
    return log_error("campaign", Error::unavailable("no sbatch on PATH: run this where Slurm's client is (Debian: slurm-client)"));
  std::error_code ec;
  campaign::SlurmOptions so;
  so.hitl = self_path();
  so.campaign_path = std::filesystem::absolute(o.file, ec).string();
  so.out_dir = std::filesystem::absolute(o.out_dir.empty() ? "campaign-" + c->name : o.out_dir, ec).lexically_normal().string();
  so.partition = o.partition;
  so.max_running = o.max_running;
  so.label = o.label;
  auto history = run_history(o.no_history, o.history);
  if (!history) return log_error("campaign", history.error());
  if (!history->empty()) so.history = std::filesystem::absolute(*history, ec).string();
  const std::size_t flights = campaign::expand(*c).size();
  auto submitted = campaign::submit_to_slurm(*c, flights, so, *sbatch);
  if (!submitted) return log_error("campaign", submitted.error());
  if (g.json) {
    print_json_line({{"type", "summary"},          {"campaign", c->name},
                     {"flights", flights},         {"flights_job", submitted->flights_job},
                     {"collect_job", submitted->collect_job}, {"out", so.out_dir},
                     {"scripts", {submitted->flights_script, submitted->collect_script}}});
  } else {
    std::cout << "campaign " << c->name << ": " << flights << " flights submitted to Slurm as job array " << submitted->flights_job
              << ", collect as job " << submitted->collect_job << " after it\n"
              << "results: " << so.out_dir << "/ (" << campaign::kCampaignSummaryFile << " and " << campaign::kJunitFile
              << " once collect has run; squeue -j " << submitted->flights_job << "," << submitted->collect_job << ")\n";
  }
  return kExitOk;
}

}  // namespace

int run_campaign_file(const GlobalOptions& options, const CampaignFileRun& run) {
  CampaignRunOptions o;
  o.file = run.file;
  o.jobs = run.jobs;
  o.out_dir = run.out_dir;
  o.history = run.history;
  o.label = run.label;
  return run_campaign_command(options, o);
}

void add_campaign_command(CLI::App& app, GlobalOptions& options, RunState& state) {
  auto* sub = app.add_subcommand("campaign", "Fly a matrix of flights (trajectories x faults x seeds) unattended: results, JUnit XML, an HTML page");
  sub->require_subcommand(1);
  sub->footer("The campaign file: docs/campaigns.md.");
  auto o = std::make_shared<CampaignRunOptions>();
  auto* run = sub->add_subcommand(
      "run", "Run a campaign file's flights against the emulated board or PX4 SITL, in parallel, into a results folder");
  run->add_option("FILE", o->file, "The campaign file (TOML, docs/campaigns.md)")->required()->check(CLI::ExistingFile)
      ->type_name("FILE.toml");
  run->add_option("-j,--jobs", o->jobs, "Flights at a time (default: the cores)")->check(number_in(1, 256))->type_name("N");
  run->add_option("--out", o->out_dir, "The results folder (default: campaign-NAME)")->type_name("DIR");
  run->add_option("--only", o->only,
                  "Fly flight INDEX alone, in this process, into the results folder (what each child runs)")
      ->check(non_negative_integer())->type_name("INDEX");
  auto* resume = run->add_flag("--resume", o->resume, "Continue a stopped run: fly only the flights without a result");
  auto* rerun = run->add_flag("--rerun-failed", o->rerun_failed, "Fly the flights without a result and those that failed");
  resume->excludes(rerun);
  auto* history = run->add_option("--history", o->history,
                                  "Add this run to the history database (SQLite; default $XDG_DATA_HOME/hitl/campaigns.sqlite, "
                                  "~/.local/share/hitl/campaigns.sqlite without XDG_DATA_HOME)")
                      ->type_name("FILE");
  run->add_option("--label", o->label, "Name this run in the history: a commit, a firmware version")->type_name("TEXT");
  run->add_flag("--no-history", o->no_history, "Keep this run out of the history")->excludes(history);
  run->add_option("--px4", o->px4_dir,
                  "With stack = \"px4\": the PX4 SITL build every flight starts (a build folder or a PX4 tree, as hitl sim "
                  "--px4 DIR), over the file's px4 = \"DIR\"")
      ->type_name("DIR");
  run->footer("Exit: 0 when every flight passed, 1 otherwise.");
  run->callback([&options, &state, o]() { state.exit_code = run_campaign_command(options, *o); });

  auto co = std::make_shared<CampaignCollectOptions>();
  auto* collect = sub->add_subcommand(
      "collect", "Gather flights run elsewhere (--only INDEX into one folder: Slurm, Kubernetes, a CI matrix) into summary.json, "
                 "junit.xml and the history");
  collect->add_option("FILE", co->file, "The campaign file the flights came from")->required()->check(CLI::ExistingFile)
      ->type_name("FILE.toml");
  collect->add_option("--out", co->out_dir, "The shared results folder (default: campaign-NAME)")->type_name("DIR");
  auto* collect_history = collect->add_option("--history", co->history, "The history database (default: as hitl campaign run)")
                              ->type_name("FILE");
  collect->add_option("--label", co->label, "Name this run in the history: a commit, a firmware version")->type_name("TEXT");
  collect->add_flag("--no-history", co->no_history, "Keep this run out of the history")->excludes(collect_history);
  collect->footer("Exit: 0 when every flight passed, 1 otherwise (a flight without a result counts as not flown).");
  collect->callback([&options, &state, co]() { state.exit_code = run_collect_command(options, *co); });

  auto mo = std::make_shared<CampaignMatrixOptions>();
  auto* matrix = sub->add_subcommand("matrix", "The flights as a GitHub Actions matrix (JSON: include, one job per flight)");
  matrix->add_option("FILE", mo->file, "The campaign file")->required()->check(CLI::ExistingFile)->type_name("FILE.toml");
  matrix->add_option("-o,--output", mo->output, "Write it here (default: standard output)")->type_name("FILE.json");
  matrix->footer("Each job runs: hitl campaign run FILE --only ${{ matrix.index }} --out DIR; then hitl campaign collect FILE "
                 "--out DIR (docs/campaigns.md). At most 256 flights (GitHub's limit).");
  matrix->callback([&state, mo]() { state.exit_code = run_matrix_command(*mo); });

  auto ko = std::make_shared<CampaignK8sOptions>();
  auto* k8s = sub->add_subcommand("k8s", "The flights as a Kubernetes Indexed Job (JSON manifest for kubectl apply -f)");
  k8s->add_option("FILE", ko->file, "The campaign file")->required()->check(CLI::ExistingFile)->type_name("FILE.toml");
  k8s->add_option("--image", ko->image, "The container image with hitl and the campaign's files")->required()->type_name("IMAGE");
  k8s->add_option("--path-in-image", ko->path_in_image, "The campaign file inside the image (default: FILE as given)")
      ->type_name("PATH");
  k8s->add_option("--claim", ko->claim, "The PersistentVolumeClaim mounted at /results for every flight")->capture_default_str()
      ->type_name("NAME");
  k8s->add_option("-j,--parallelism", ko->parallelism, "Pods at a time (default: every flight)")->check(number_in(1, 10000))
      ->type_name("N");
  k8s->add_option("-o,--output", ko->output, "Write it here (default: standard output)")->type_name("FILE.json");
  k8s->footer("Each pod runs hitl campaign run PATH --only $JOB_COMPLETION_INDEX --out /results/JOB; then hitl campaign collect "
              "on the claim (docs/campaigns.md).");
  k8s->callback([&state, ko]() { state.exit_code = run_k8s_command(*ko); });

  auto so = std::make_shared<CampaignSlurmOptions>();
  auto* slurm = sub->add_subcommand("slurm", "Submit the flights to Slurm as a job array (sbatch --array), collect after it");
  slurm->add_option("FILE", so->file, "The campaign file (every node reads it, the results folder and this hitl at the same "
                                      "paths: a shared file system)")
      ->required()->check(CLI::ExistingFile)->type_name("FILE.toml");
  slurm->add_option("--out", so->out_dir, "The results folder, shared by the nodes (default: campaign-NAME)")->type_name("DIR");
  slurm->add_option("--partition", so->partition, "The Slurm partition (default: the cluster's)")->type_name("NAME");
  slurm->add_option("-j,--max-running", so->max_running, "At most N flights at once (the array's %N; default: as Slurm schedules)")
      ->check(number_in(1, 10000))->type_name("N");
  auto* slurm_history = slurm->add_option("--history", so->history, "collect's history database (default: as hitl campaign run)")
                            ->type_name("FILE");
  slurm->add_option("--label", so->label, "Name this run in the history: a commit, a firmware version")->type_name("TEXT");
  slurm->add_flag("--no-history", so->no_history, "Keep this run out of the history")->excludes(slurm_history);
  slurm->footer("Writes OUT/slurm/flights.sbatch (a task per flight: hitl campaign run FILE --only $SLURM_ARRAY_TASK_ID, "
                "--time the campaign's time_limit_s) and OUT/slurm/collect.sbatch (--dependency=afterany), submits both; "
                "each task's output in OUT/slurm/flight-N.out. Exit: 0 submitted, 1 sbatch refused, 2 no sbatch.");
  slurm->callback([&options, &state, so]() { state.exit_code = run_slurm_command(options, *so); });

  auto ho = std::make_shared<CampaignHistoryOptions>();
  auto* hist = sub->add_subcommand("history", "Per-criterion trends of a campaign's runs from the history, regressions flagged");
  hist->add_option("NAME", ho->campaign, "The campaign (default: the one run last)");
  hist->add_option("--history", ho->history, "The history database (default: as hitl campaign run)")->type_name("FILE");
  hist->add_option("--last", ho->last_runs, "How many of the latest runs to show (at least 2)")->capture_default_str()
      ->check(number_in(2, 1000))->type_name("N");
  hist->footer("A regression: the latest run's mean (failures for an equals criterion) worse than the runs before it by more "
               "than their spread. Exit: 0 none, 1 a regression, 2 no such history or campaign.");
  hist->callback([&options, &state, ho]() { state.exit_code = run_history_command(options, *ho); });
}

}  // namespace hitl::cli
