// hitl params: PX4 parameters from the host: show, get, set, diff and check against the spec's
// HITL set, export/load in QGroundControl's .params format, and reset to the HITL defaults.
#include <fnmatch.h>
#include <unistd.h>

#include <algorithm>
#include <optional>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>

#include "cli/commands.h"
#include "cli/link_options.h"
#include "cli/parse_errors.h"
#include "engine/vehicle/firmware_version.h"
#include "engine/vehicle/param_client.h"
#include "engine/vehicle/param_notes.h"
#include "engine/vehicle/params_check.h"
#include "engine/vehicle/params_file.h"
#include "engine/vehicle/params_push.h"

namespace hitl::cli {
namespace {

struct ParamsOptions {
  vehicle::LinkOptions link;
  std::string pattern;
  std::string name;
  std::string value;
  std::string file;
  bool dry_run = false;
  bool strict = false;  ///< check/diff/reset: a parameter this firmware lacks fails too
};

nlohmann::json to_json(const vehicle::ParamValue& v) {
  return v.type == vehicle::ParamType::Int32 ? nlohmann::json(v.i) : nlohmann::json(v.f);
}

nlohmann::json change(const std::string& name, const vehicle::ParamValue& from, const vehicle::ParamValue& to) {
  return {{"name", name}, {"from", to_json(from)}, {"to", to_json(to)}, {"from_text", from.to_string()}, {"to_text", to.to_string()}};
}

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

/// What a run says when it ends: errors on stderr and, with --json, the one summary every command
/// ends with (README: status objects while running, exactly one {"type":"summary"} last):
/// {"type":"summary","command":"params","action":"get",...}. A run that ends on an error without one
/// gets {"ok":false,"error":...} (finish()).
struct Report {
  const GlobalOptions& g;
  std::string action;
  bool summarised = false;
  std::string first_error;

  void fail(const std::string& message) {
    log_error("params", message);
    if (first_error.empty()) first_error = message;
  }
  void summary(nlohmann::json body) {
    if (!g.json) return;
    body["type"] = "summary";
    body["command"] = "params";
    body["action"] = action;
    if (!body.contains("ok")) body["ok"] = true;
    print_json_line(body);
    summarised = true;
  }
  void finish() {
    if (g.json && !summarised) summary({{"ok", false}, {"error", first_error}});
  }
};

/// Connects and downloads, saying how; an error line and the error on failure.
struct Session {
  std::unique_ptr<vehicle::VehicleLink> link;
  std::unique_ptr<vehicle::ParamClient> client;
};

Expected<Session> open(Report& report, const ParamsOptions& o) {
  const GlobalOptions& g = report.g;
  auto link = vehicle::VehicleLink::connect(o.link);
  if (!link) {
    report.fail(link.error().message);
    return link.error();
  }
  log_info(g, "hitl params: autopilot " + std::to_string((*link)->target_sysid()) + " " + (*link)->description());
  Session s;
  s.link = std::move(link.value());
  s.client = std::make_unique<vehicle::ParamClient>(*s.link);
  return s;
}

Expected<std::vector<vehicle::Param>> download(Report& report, Session& s) {
  const GlobalOptions& g = report.g;
  const bool tty = ::isatty(STDERR_FILENO) == 1 && !g.quiet;
  auto all = s.client->download([&](std::size_t n, std::size_t total) {
    if (tty && (n % 25 == 0 || n == total)) std::fprintf(stderr, "\rparameters %zu / %zu", n, total);
  });
  if (tty) std::fprintf(stderr, "\n");
  if (!all) report.fail(all.error().message);
  return all;
}

/// Why `get` of `name` failed, in words: when the board's list has no such name, says so with the
/// closest name it has ("did you mean 'SYS_HITL'?", parse_errors' closest()); else the client's error.
std::string explain_get_failure(Session& s, const std::string& name, const std::string& error) {
  auto all = s.client->download();
  if (!all) return error;
  std::vector<std::string> names;
  names.reserve(all->size());
  for (const auto& p : *all) {
    if (p.name == name) return error;  // it exists: the failure was the answer, not the name
    names.push_back(p.name);
  }
  const auto guess = closest(name, names);
  return "the board has no parameter " + name + " (" + std::to_string(names.size()) + " downloaded)" +
         (guess ? "; did you mean '" + *guess + "'?" : "; `hitl params show 'PREFIX*'` lists them");
}

/// "this firmware (v1.16.0)" or "this firmware" when AUTOPILOT_VERSION does not come.
std::string this_firmware(const std::optional<std::string>& version) {
  return version ? "this firmware (" + *version + ")" : std::string("this firmware");
}

nlohmann::json version_json(const std::optional<std::string>& version) {
  return version ? nlohmann::json(*version) : nlohmann::json(nullptr);
}

/// Pushes `wanted` onto the board: set what differs, verify by read-back, report.
/// `absent_ok` (reset of the HITL set): a parameter the board does not have is reported as absent,
/// a failure only with --strict; otherwise (load) it fails.
int push(Report& report, const ParamsOptions& o, Session& s, const std::vector<vehicle::Param>& wanted, bool absent_ok) {
  const GlobalOptions& g = report.g;
  const bool dry_run = o.dry_run;
  auto board = download(report, s);
  if (!board) return exit_code(board.error());
  const auto pushed = vehicle::push_params(*s.client, *s.link, *board, wanted, {dry_run, absent_ok});
  const std::optional<std::string>& firmware = pushed.firmware;
  nlohmann::json set = nlohmann::json::array(), unchanged = pushed.unchanged, failed = nlohmann::json::array(),
                 absent = nlohmann::json::array();
  for (const auto& c : pushed.set) set.push_back(change(c.name, c.from, c.to));
  for (const auto& f : pushed.failed) failed.push_back({{"name", f.name}, {"error", f.error}});
  for (const auto& a : pushed.absent)
    absent.push_back({{"name", a.name},
                      {"note", a.note ? nlohmann::json("not in " + a.note->firmware + ": " + a.note->replacement) : nlohmann::json(nullptr)}});
  const bool ok = pushed.ok(o.strict);
  if (g.json) {
    nlohmann::json out = {{"dry_run", dry_run}, {"set", set}, {"unchanged", unchanged}, {"failed", failed}, {"ok", ok}};
    if (absent_ok) {
      out["absent"] = absent;
      out["firmware"] = version_json(firmware);
      out["strict"] = o.strict;
    }
    report.summary(out);
  } else {
    for (const auto& e : set)
      std::cout << (dry_run ? "would set " : "set ") << e["name"].get<std::string>() << ": " << e["from_text"].get<std::string>()
                << " -> " << e["to_text"].get<std::string>() << '\n';
    for (const auto& e : failed) std::cout << "FAILED " << e["name"].get<std::string>() << ": " << e["error"].get<std::string>() << '\n';
    for (const auto& e : absent) {
      std::cout << "ABSENT " << e["name"].get<std::string>() << ": " << this_firmware(firmware) << " has no such parameter";
      if (!e["note"].is_null()) std::cout << "  -> " << e["note"].get<std::string>();
      std::cout << '\n';
    }
    std::cout << set.size() << (dry_run ? " to set, " : " set, ") << unchanged.size() << " unchanged, " << failed.size() << " failed";
    if (absent_ok) std::cout << ", " << absent.size() << " absent" << (absent.empty() || o.strict ? "" : " (not a failure; --strict to count them)");
    std::cout << '\n';
  }
  return ok ? kExitOk : kExitFailed;
}

int run_action(Report& report, const ParamsOptions& o, const std::string& action) {
  const GlobalOptions& g = report.g;
  // A bad file is refused before anything talks to the board.
  std::optional<Expected<std::vector<vehicle::Param>>> file;
  if (action == "load") {
    file.emplace(vehicle::load_params_file(o.file));
    if (!*file) {
      report.fail((*file).error().message);
      return exit_code((*file).error());
    }
  }
  auto s = open(report, o);
  if (!s) return exit_code(s.error());
  if (action == "show" || action == "export") {
    auto all = download(report, *s);
    if (!all) return exit_code(all.error());
    if (action == "export") {
      std::ofstream f(o.file);
      f << vehicle::format_params(*all, s->link->target_sysid(), s->link->target_compid());
      if (!f) {
        const Error unwritable = Error::unavailable("cannot write '" + o.file + "'");
        report.fail(unwritable.message);
        return exit_code(unwritable);
      }
      if (g.json) report.summary({{"file", o.file}, {"count", all->size()}});
      else std::cout << "exported " << all->size() << " parameters to " << o.file << '\n';
      return kExitOk;
    }
    const std::string pattern = upper(o.pattern.empty() ? "*" : o.pattern);
    nlohmann::json params = nlohmann::json::object();
    for (const auto& p : *all) {
      if (fnmatch(pattern.c_str(), p.name.c_str(), 0) != 0) continue;
      if (g.json) params[p.name] = to_json(p.value);
      else std::printf("%-16s %s\n", p.name.c_str(), p.value.to_string().c_str());
    }
    if (g.json) report.summary({{"params", params}});
    return kExitOk;
  }
  if (action == "get") {
    auto v = s->client->get(upper(o.name));
    if (!v) {
      report.fail(explain_get_failure(*s, upper(o.name), v.error().message));
      return exit_code(v.error());
    }
    if (g.json) report.summary({{"name", upper(o.name)}, {"value", to_json(*v)}});
    else std::cout << v->to_string() << '\n';
    return kExitOk;
  }
  if (action == "set") {
    const std::string name = upper(o.name);
    auto current = s->client->get(name);
    if (!current) {
      report.fail(explain_get_failure(*s, name, current.error().message));
      return exit_code(current.error());
    }
    const auto wanted = vehicle::parse_param_value(o.value, current->type);
    if (!wanted) {
      report.fail("set " + name + ": " + wanted.error().message);
      return exit_code(wanted.error());
    }
    auto r = s->client->set(name, *wanted);
    if (!r) {
      report.fail(r.error().message);
      return exit_code(r.error());
    }
    if (g.json) report.summary({{"name", name}, {"value", to_json(*r)}, {"previous", to_json(*current)}});
    else std::cout << name << ": " << current->to_string() << " -> " << r->to_string() << '\n';
    return kExitOk;
  }
  if (action == "diff" || action == "check") {
    auto all = download(report, *s);
    if (!all) return exit_code(all.error());
    const auto checked = vehicle::check_params(*all, vehicle::hitl_default_params());
    std::optional<std::string> firmware;
    nlohmann::json absent = nlohmann::json::array();
    for (const auto& c : checked)
      if (c.absent) absent.push_back(c.name);
    if (!absent.empty()) firmware = vehicle::request_firmware_version(*s->link);
    nlohmann::json rows = nlohmann::json::array();
    bool all_ok = true;
    for (const auto& c : checked) {
      all_ok = all_ok && !vehicle::row_fails(c, o.strict);
      if (action == "diff" && c.ok) continue;
      nlohmann::json row = {{"name", c.name}, {"expected", to_json(c.expected)},
                            {"board", c.board ? to_json(*c.board) : nlohmann::json(nullptr)}, {"ok", c.ok},
                            {"absent", c.absent}, {"note", c.note.empty() ? nlohmann::json(nullptr) : nlohmann::json(c.note)}};
      if (!c.ok) row["fix"] = c.fix;
      rows.push_back(row);
    }
    if (g.json) {
      report.summary({{action == "diff" ? "differences" : "checks", rows}, {"ok", all_ok},
                       {"absent", absent}, {"firmware", version_json(firmware)}, {"strict", o.strict}});
    } else {
      for (const auto& c : checked) {
        if (action == "diff" && c.ok) continue;
        if (c.absent) {
          std::cout << "ABSENT " << c.name << ": " << this_firmware(firmware) << " has no such parameter, HITL default "
                    << c.expected.to_string();
          if (!c.note.empty()) std::cout << "  -> " << c.note;
          std::cout << '\n';
          continue;
        }
        if (action == "check") std::cout << (c.ok ? "PASS " : "FAIL ");
        std::cout << c.name << ": board " << c.board->to_string() << ", HITL default " << c.expected.to_string();
        if (!c.ok) std::cout << "  -> " << c.fix;
        std::cout << '\n';
      }
      const std::size_t wrong = std::count_if(checked.begin(), checked.end(), [](const auto& c) { return !c.ok && !c.absent; });
      if (action == "diff" && wrong == 0) std::cout << "no differences from the HITL defaults\n";
      if (!absent.empty())
        std::cout << absent.size() << " absent on " << this_firmware(firmware)
                  << (o.strict ? " (--strict: counted as failures)\n" : " (not a failure; --strict to count them)\n");
    }
    return all_ok ? kExitOk : kExitFailed;
  }
  if (action == "load") return push(report, o, *s, **file, false);
  return push(report, o, *s, vehicle::hitl_default_params(), true);
}

int run(const GlobalOptions& g, const ParamsOptions& o, const std::string& action) {
  Report report{g, action};
  const int code = run_action(report, o, action);
  report.finish();
  return code;
}

}  // namespace

void add_params_command(CLI::App& app, GlobalOptions& options, RunState& state) {
  auto o = std::make_shared<ParamsOptions>();
  auto* sub = app.add_subcommand("params", "PX4 parameters: show, get, set, diff/check against the HITL set, export, load, reset");
  sub->require_subcommand(1);
  sub->footer("Exit: 0 ok, 1 a check failed or the board did not take a value (a parameter this firmware lacks: only\n"
              "with --strict), 2 bad usage or file.");
  add_link_options(sub, o->link);
  auto add = [&](const char* name, const char* help) {
    auto* c = sub->add_subcommand(name, help);
    c->callback([&options, &state, o, action = std::string(name)]() { state.exit_code = run(options, *o, action); });
    return c;
  };
  add("show", "List parameters (all, or those matching a glob such as 'EKF2_*')")->add_option("PATTERN", o->pattern, "Glob");
  add("get", "Print one parameter's value")->add_option("NAME", o->name)->required();
  auto* set = add("set", "Set one parameter and check the board's echo");
  set->add_option("NAME", o->name)->required();
  set->add_option("VALUE", o->value)->required();
  const char* strict_help = "Count a parameter of the HITL set that this firmware lacks as a failure (default: reported as absent)";
  add("diff", "Parameters that differ from the spec's HITL default set (exit 1 when any)")->add_flag("--strict", o->strict, strict_help);
  add("check", "The spec's HITL settings (SYS_HITL, CAL_*_ID vs the dsp_hitl device IDs, EKF2, arming, CA_*): "
               "pass/fail with the command that fixes each; parameters this firmware lacks as absent")
      ->add_flag("--strict", o->strict, strict_help);
  add("export", "Save every parameter to a QGroundControl .params file")->add_option("FILE", o->file)->required();
  auto* load = add("load", "Set the parameters of a .params file, verified by read-back");
  load->add_option("FILE", o->file)->required()->check(CLI::ExistingFile);
  load->add_flag("--dry-run", o->dry_run, "Show what would change");
  auto* reset = add("reset", "Push the spec's HITL default set, verified by read-back (no rm on the board needed)");
  reset->add_flag("--dry-run", o->dry_run, "Show what would change");
  reset->add_flag("--strict", o->strict, strict_help);
}

}  // namespace hitl::cli
