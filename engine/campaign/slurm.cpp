#include "engine/campaign/slurm.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "base/common/shell_quote.h"
#include "engine/campaign/work_units.h"
#include "engine/net/child_process.h"

namespace hitl::campaign {
namespace {

constexpr int kSbatchTimeout_ms = 60000;

std::string header(const std::string& job_name, const SlurmOptions& o) {
  std::string s = "#!/bin/sh\n#SBATCH --job-name=" + job_name + "\n";
  if (!o.partition.empty()) s += "#SBATCH --partition=" + o.partition + "\n";
  return s;
}

Status write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  if (!(out << text)) return Error::unavailable("cannot write " + path);
  return Ok{};
}

/// sbatch --parsable's answer: "JOBID" or "JOBID;CLUSTER".
Expected<std::string> submit(const std::string& sbatch, const std::vector<std::string>& args) {
  auto r = net::run_program(sbatch, args, kSbatchTimeout_ms);
  if (!r) return r.error();
  std::string id = r->out.substr(0, r->out.find_first_of(";\n"));
  if (r->exit_code != 0 || id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
    return Error::failed(net::command_line(sbatch, args) + " refused (exit " + std::to_string(r->exit_code) +
                              "): " + (r->err.empty() ? r->out : r->err));
  return id;
}

}  // namespace

std::string slurm_time(double seconds) {
  const long long s = static_cast<long long>(std::ceil(std::max(1.0, seconds)));
  char text[32];
  std::snprintf(text, sizeof text, "%lld:%02lld", s / 60, s % 60);
  return text;
}

std::string slurm_flights_script(const Campaign& campaign, std::size_t flights, const SlurmOptions& o) {
  const std::string job = k8s_job_name(campaign.name);
  std::string s = header(job, o);
  s += "#SBATCH --array=0-" + std::to_string(flights == 0 ? 0 : flights - 1) +
       (o.max_running > 0 ? "%" + std::to_string(o.max_running) : "") + "\n";
  s += "#SBATCH --time=" + slurm_time(campaign.time_limit_s) + "\n";
  s += "#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=1\n";
  s += "#SBATCH --output=" + o.out_dir + "/slurm/flight-%a.out\n";
  s += "# One flight of campaign " + campaign.name + " per task (docs/campaigns.md). Exit 1 is a flight that failed\n"
       "# its criteria: a result like any other, so the task still succeeds.\n";
  s += shell_quoted(o.hitl) + " campaign run " + shell_quoted(o.campaign_path) + " --only \"$SLURM_ARRAY_TASK_ID\" --out " +
       shell_quoted(o.out_dir) + "\nrc=$?\n[ \"$rc\" -le 1 ]\n";
  return s;
}

std::string slurm_collect_script(const Campaign& campaign, const SlurmOptions& o) {
  std::string s = header(k8s_job_name(campaign.name) + "-collect", o);
  s += "#SBATCH --time=" + slurm_time(300) + "\n#SBATCH --ntasks=1\n";
  s += "#SBATCH --output=" + o.out_dir + "/slurm/collect.out\n";
  s += "# Every flight's result into summary.json, junit.xml and the history, once every task has ended.\n";
  s += shell_quoted(o.hitl) + " campaign collect " + shell_quoted(o.campaign_path) + " --out " + shell_quoted(o.out_dir);
  s += o.history.empty() ? std::string(" --no-history") : " --history " + shell_quoted(o.history);
  if (!o.label.empty()) s += " --label " + shell_quoted(o.label);
  s += "\nrc=$?\n[ \"$rc\" -le 1 ]\n";
  return s;
}

Expected<SlurmSubmission> submit_to_slurm(const Campaign& campaign, std::size_t flights, const SlurmOptions& o,
                                          const std::string& sbatch) {
  std::error_code ec;
  const std::string dir = o.out_dir + "/slurm";
  std::filesystem::create_directories(dir, ec);
  if (ec) return Error::unavailable("cannot make " + dir + ": " + ec.message());
  SlurmSubmission s;
  s.flights_script = dir + "/flights.sbatch";
  s.collect_script = dir + "/collect.sbatch";
  if (auto ok = write_file(s.flights_script, slurm_flights_script(campaign, flights, o)); !ok) return ok.error();
  if (auto ok = write_file(s.collect_script, slurm_collect_script(campaign, o)); !ok) return ok.error();
  auto array = submit(sbatch, {"--parsable", "--chdir=" + o.out_dir, s.flights_script});
  if (!array) return array.error();
  s.flights_job = *array;
  auto collect = submit(sbatch, {"--parsable", "--chdir=" + o.out_dir, "--dependency=afterany:" + s.flights_job, s.collect_script});
  if (!collect) return collect.error().prefixed("the array " + s.flights_job + " is submitted, but collect is not: ");
  s.collect_job = *collect;
  return s;
}

}  // namespace hitl::campaign
