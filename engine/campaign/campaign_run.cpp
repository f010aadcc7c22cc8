#include "engine/campaign/campaign_run.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>

extern char** environ;

namespace hitl::campaign {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

struct Child {
  const Flight* flight = nullptr;
  pid_t pid = -1;
  Clock::time_point started;
  bool timed_out = false;
};

/// Starts the flight's child: its own process group, stdin /dev/null, stdout and stderr into log.txt.
Expected<pid_t> spawn_child(const RunOptions& o, const Flight& flight) {
  const std::string folder = flight_folder(o.out_dir, flight);
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) return Error::unavailable("cannot make " + folder + ": " + ec.message());
  std::filesystem::remove(std::filesystem::path(folder) / kResultFile, ec);
  const std::string log = (std::filesystem::path(folder) / kLogFile).string();
  std::vector<std::string> args = o.child_args(flight);
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(o.program.c_str()));
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  posix_spawnattr_setpgroup(&attr, 0);  // its own group: a terminal's Ctrl-C reaches the runner, which stops it
  sigset_t defaults, none;
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGINT);
  sigaddset(&defaults, SIGTERM);
  sigaddset(&defaults, SIGPIPE);
  sigemptyset(&none);
  posix_spawnattr_setsigdefault(&attr, &defaults);
  posix_spawnattr_setsigmask(&attr, &none);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK);
  pid_t pid = -1;
  const int spawned = ::posix_spawn(&pid, o.program.c_str(), &actions, &attr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  if (spawned != 0) return Error::unavailable("cannot start " + o.program + " for flight " + flight.name + ": " + std::strerror(spawned));
  return pid;
}

/// The log's last non-empty line (bounded), for an error's reason.
std::string last_log_line(const std::string& folder) {
  std::ifstream in((std::filesystem::path(folder) / kLogFile).string(), std::ios::binary);
  if (!in) return "";
  in.seekg(0, std::ios::end);
  const auto size = static_cast<long long>(in.tellg());
  const long long from = size > 4096 ? size - 4096 : 0;
  in.seekg(from);
  std::string tail((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  while (!tail.empty() && (tail.back() == '\n' || tail.back() == '\r')) tail.pop_back();
  const auto nl = tail.rfind('\n');
  std::string line = nl == std::string::npos ? tail : tail.substr(nl + 1);
  if (line.size() > 300) line = line.substr(0, 300) + "...";
  return line;
}

void append_log(const std::string& folder, const std::string& line) {
  std::ofstream out((std::filesystem::path(folder) / kLogFile).string(), std::ios::app);
  out << "hitl campaign: " << line << '\n';
}

/// What a finished child leaves: its result, or an error result saying why there is none.
FlightResult collect(const Campaign& campaign, const RunOptions& o, const Child& child, int status) {
  const std::string folder = flight_folder(o.out_dir, *child.flight);
  const double process_s = seconds_since(child.started);
  auto read = read_result(folder);
  const bool exited = WIFEXITED(status) && (WEXITSTATUS(status) == 0 || WEXITSTATUS(status) == 1);
  if (read && exited && !child.timed_out) {
    read->process_wall_s = process_s;
    (void)write_result(folder, *read);
    return *read;
  }
  FlightResult r;
  r.index = child.flight->index;
  r.id = child.flight->id;
  r.name = child.flight->name;
  r.outcome = "error";
  char limit[32];
  std::snprintf(limit, sizeof limit, "%g", campaign.time_limit_s);
  if (child.timed_out)
    r.reason = std::string("no result within the time limit of ") + limit + " s (campaign.time_limit_s): killed";
  else
    r.reason = wait_status_text(status) + " without a result";
  const std::string last = last_log_line(folder);
  append_log(folder, r.reason);
  if (!last.empty()) r.reason += "; its log's last line: " + last;
  r.summary_line = r.name + ": error: " + r.reason;
  r.process_wall_s = process_s;
  (void)write_result(folder, r);
  return r;
}

bool wanted(RunMode mode, const std::optional<FlightResult>& earlier) {
  if (!earlier) return true;
  return mode == RunMode::RerunFailed && earlier->outcome != "passed";
}

}  // namespace

std::string wait_status_text(int status) {
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    const char* abbrev = sigabbrev_np(sig);
    const std::string name = abbrev != nullptr ? std::string(" (SIG") + abbrev + ")" : "";
    return (sig == SIGKILL || sig == SIGTERM || sig == SIGINT ? "killed by signal " : "crashed: signal ") + std::to_string(sig) +
           name;
  }
  if (WIFEXITED(status)) return "exited with status " + std::to_string(WEXITSTATUS(status));
  return "ended with wait status " + std::to_string(status);
}

std::vector<std::optional<FlightResult>> read_results(const std::string& out_dir, const std::vector<Flight>& flights) {
  std::vector<std::optional<FlightResult>> out(flights.size());
  for (const auto& f : flights) {
    auto r = read_result(flight_folder(out_dir, f));
    if (r && r->id == f.id) {
      r->index = f.index;  // its place in this expansion
      out[f.index] = std::move(r.value());
    }
  }
  return out;
}

Expected<RunOutcome> run_campaign(const Campaign& campaign, const std::vector<Flight>& flights, const RunOptions& o,
                                  const std::atomic<bool>& stop, RunObserver& observer) {
  const auto started = Clock::now();
  std::error_code ec;
  std::filesystem::create_directories(std::filesystem::path(o.out_dir) / "flights", ec);
  if (ec) return Error::unavailable("cannot make the results folder " + o.out_dir + ": " + ec.message());
  auto earlier = read_results(o.out_dir, flights);
  std::vector<const Flight*> queue;
  RunOutcome out;
  for (const auto& f : flights) {
    if (wanted(o.mode, earlier[f.index])) queue.push_back(&f);
    else ++out.progress.kept;
  }
  if (o.mode == RunMode::Fresh && out.progress.kept > 0)
    return Error::usage(o.out_dir + " holds results of an earlier run (" + std::to_string(out.progress.kept) +
                        " flights): --resume flies only the missing ones, --rerun-failed also the failed ones; or give another --out");
  out.progress.total = queue.size();
  std::vector<Child> running;
  std::size_t next = 0;
  auto last_progress = Clock::now();
  bool stopping = false;
  Clock::time_point stop_started;
  auto report_progress = [&] {
    out.progress.running = running.size();
    out.progress.elapsed_s = seconds_since(started);
    if (out.progress.done > 0 && out.progress.total > out.progress.done) {
      const double per_flight = out.progress.elapsed_s / static_cast<double>(out.progress.done);
      out.progress.eta_s = per_flight * static_cast<double>(out.progress.total - out.progress.done);
    } else if (out.progress.total == out.progress.done) {
      out.progress.eta_s = 0.0;
    }
    observer.on_progress(out.progress);
    last_progress = Clock::now();
  };
  report_progress();
  const std::size_t jobs = o.jobs == 0 ? 1 : o.jobs;
  while (true) {
    if (stop && !stopping) {
      stopping = true;
      stop_started = Clock::now();
      for (const auto& c : running) ::kill(-c.pid, SIGTERM);
    }
    if (stopping && seconds_since(stop_started) > o.stop_grace_s)
      for (const auto& c : running) ::kill(-c.pid, SIGKILL);
    while (!stopping && running.size() < jobs && next < queue.size()) {
      const Flight& f = *queue[next++];
      auto pid = spawn_child(o, f);
      if (!pid) {
        FlightResult r;
        r.index = f.index;
        r.id = f.id;
        r.name = f.name;
        r.outcome = "error";
        r.reason = pid.error().message;
        r.summary_line = r.name + ": error: " + r.reason;
        (void)write_result(flight_folder(o.out_dir, f), r);
        ++out.progress.done;
        ++out.progress.failed;
        observer.on_finished(f, r);
        continue;
      }
      running.push_back(Child{&f, *pid, Clock::now(), false});
      observer.on_started(f, *pid);
      report_progress();
    }
    if (running.empty() && (stopping || next >= queue.size())) break;
    bool changed = false;
    for (auto it = running.begin(); it != running.end();) {
      int status = 0;
      const pid_t done = ::waitpid(it->pid, &status, WNOHANG);
      if (done == 0) {
        if (!it->timed_out && seconds_since(it->started) > campaign.time_limit_s) {
          it->timed_out = true;
          ::kill(-it->pid, SIGKILL);
        }
        ++it;
        continue;
      }
      ::kill(-it->pid, SIGKILL);  // whatever the flight left in its group
      if (stopping && !it->timed_out && !(WIFEXITED(status) && read_result(flight_folder(o.out_dir, *it->flight)))) {
        it = running.erase(it);  // stopped: no result, a resumed run flies it again
        changed = true;
        continue;
      }
      const FlightResult r = collect(campaign, o, *it, done < 0 ? 0 : status);
      ++out.progress.done;
      if (r.outcome == "passed") ++out.progress.passed;
      else ++out.progress.failed;
      observer.on_finished(*it->flight, r);
      it = running.erase(it);
      changed = true;
    }
    if (changed || seconds_since(last_progress) >= 1.0) report_progress();
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  out.stopped = stopping;
  report_progress();
  out.wall_s = seconds_since(started);
  out.results = read_results(o.out_dir, flights);
  return out;
}

}  // namespace hitl::campaign
