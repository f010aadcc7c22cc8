// The real-time cost and timing of `hitl sim`, measured from outside as a board sees it (issue 25),
// in one run:
//  1. real time: `hitl sim` with VIO and a truth client on, against a stand-in board that answers
//     each HIL_SENSOR with HIL_ACTUATOR_CONTROLS (time_usec echoed, flags 0x0F) as a board in HIL
//     mode does. HIL_SENSOR inter-arrival from the kernel's receive timestamps (SO_TIMESTAMPNS):
//     mean, std, p99, max; the session's CPU as % of one core, its wake-ups (voluntary context
//     switches) and preemptions (involuntary ones) per tick, from /proc/PID/task/*/schedstat and
//     status between its first and last status line. docs/sim.md "Measured" has the JSON fields.
//  2. lockstep as fast as possible (--lockstep --speed 0) against the same stand-in: real-time
//     factor and hitl's CPU per step.
//  3. lockstep as fast as possible against `hitl target --lockstep`: real-time factor and the CPU
//     per step of both.
//  0. the floor: a loop with no simulator in it that makes the same system calls and sends the same
//     traffic as part 1 (timing_floor.cpp), measured the same way: what this machine charges any
//     simulator at 250 Hz, so part 1 minus part 0 is hitl's own share (--floor-sendmmsg: its two
//     sends per tick in one sendmmsg).
// Prints figures (or one JSON object with --json); asserts nothing.
//
// Usage: sim_timing_bench [--seconds S] [--lockstep-seconds S] [--runs N] [--json] [--hitl PATH]
//                         [--floor-sendmmsg] [--only floor|realtime|standin|target] [-- EXTRA hitl sim ARGS...]
// e.g. sim_timing_bench --runs 3 --json -- --realtime
#include <poll.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <numeric>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "base/contract/hil_actuators.h"
#include "bench/sim/timing_floor.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/messages.h"
#include "tests/support/mavlink_peer.h"
#include "tests/support/process.h"

using namespace std::chrono_literals;
namespace msg = hitl::mavlink::msg;
using hitl::test::MavlinkPeer;
using hitl::test::Process;
using nlohmann::json;

namespace {

constexpr double kSensorPeriod_us = 4000.0;  // HIL_SENSOR at 250 Hz

// --- the process under measurement, read from /proc ---------------------------------------------

struct Usage {
  double cpu_s = 0;           ///< on-CPU time of every thread (schedstat, ns resolution)
  uint64_t switches = 0;      ///< voluntary context switches of every thread (it slept: a wake-up each)
  uint64_t preempted = 0;     ///< involuntary ones (another task took the core)
  long rss_peak_kb = 0;
  std::chrono::steady_clock::time_point at;
};

Usage usage_of(int pid) {
  Usage u;
  u.at = std::chrono::steady_clock::now();
  const std::string dir = "/proc/" + std::to_string(pid);
  std::error_code ec;
  for (const auto& task : std::filesystem::directory_iterator(dir + "/task", ec)) {
    std::ifstream sched(task.path() / "schedstat");
    double ns = 0;
    if (sched >> ns) u.cpu_s += ns * 1e-9;
    std::ifstream status(task.path() / "status");
    std::string line;
    while (std::getline(status, line))
      if (line.rfind("voluntary_ctxt_switches:", 0) == 0) u.switches += std::stoull(line.substr(line.find(':') + 1));
      else if (line.rfind("nonvoluntary_ctxt_switches:", 0) == 0) u.preempted += std::stoull(line.substr(line.find(':') + 1));
  }
  std::ifstream status(dir + "/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) u.rss_peak_kb = std::stol(line.substr(6));
  return u;
}

double seconds_between(const Usage& a, const Usage& b) { return std::chrono::duration<double>(b.at - a.at).count(); }

// --- statistics -------------------------------------------------------------------------------

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())))];
}

json summarize(const std::vector<double>& v_us) {
  if (v_us.size() < 2) return json{{"n", v_us.size()}};
  const double mean = std::accumulate(v_us.begin(), v_us.end(), 0.0) / static_cast<double>(v_us.size());
  double var = 0;
  for (double x : v_us) var += (x - mean) * (x - mean);
  // The VM stalls every process now and then for milliseconds (the floor shows the same ones): the
  // std of the middle 99.8 % and a count of the gaps over 1 ms more say what the loop itself does.
  const double lo = percentile(v_us, 0.001), hi = percentile(v_us, 0.999);
  double sum = 0, sum2 = 0, n = 0;
  for (double x : v_us)
    if (x >= lo && x <= hi) {
      sum += x;
      sum2 += x * x;
      ++n;
    }
  const double trimmed_std = n > 1 ? std::sqrt(std::max(0.0, (sum2 - sum * sum / n) / (n - 1))) : 0.0;
  const auto stalls = std::count_if(v_us.begin(), v_us.end(), [](double x) { return x > kSensorPeriod_us + 1000.0; });
  return json{{"n", v_us.size()},
              {"mean_us", mean},
              {"std_us", std::sqrt(var / static_cast<double>(v_us.size() - 1))},
              {"std_middle_99_8_us", trimmed_std},
              {"p50_us", percentile(v_us, 0.5)},
              {"p99_us", percentile(v_us, 0.99)},
              {"max_us", *std::max_element(v_us.begin(), v_us.end())},
              {"gaps_over_period_plus_1ms", stalls}};
}

// --- the stand-in board, the VIO server and a truth client, on one thread ----------------------

/// Answers each HIL_SENSOR at once with HIL_ACTUATOR_CONTROLS echoing its time_usec (as PX4 in
/// lockstep and hitl target --lockstep stamp theirs), records the kernel's receive times, drains
/// the VIO port, and keeps a truth client known to the session's client port.
class StandIn {
 public:
  StandIn(uint16_t board_port, uint16_t sim_port, uint16_t vio_port, uint16_t clients_port)
      : board_(board_port, sim_port), vio_(vio_port, 0), truth_(0, clients_port, 255, 190), parser_(set_) {
    thread_ = std::thread([this] { loop(); });
  }
  ~StandIn() {
    stop_ = true;
    thread_.join();
  }
  /// Kernel receive times of every HIL_SENSOR so far, ns (CLOCK_REALTIME).
  std::vector<int64_t> sensor_times_ns() {
    std::lock_guard<std::mutex> lock(mutex_);
    return sensor_ns_;
  }
  uint64_t vio_frames() const { return vio_frames_.load(); }
  uint64_t truth_frames() const { return truth_frames_.load(); }

 private:
  void loop() {
    auto next_heartbeat = std::chrono::steady_clock::now();
    hitl::mavlink::FrameParser vio_parser(set_), truth_parser(set_);
    while (!stop_) {
      if (std::chrono::steady_clock::now() >= next_heartbeat) {
        next_heartbeat += 1s;
        msg::Heartbeat hb;
        hb.type = 6;  // MAV_TYPE_GCS: a client the session learns from what it sends
        truth_.send(hb);
      }
      pollfd fds[3] = {{board_.endpoint().fd(), POLLIN, 0}, {vio_.endpoint().fd(), POLLIN, 0}, {truth_.endpoint().fd(), POLLIN, 0}};
      if (::poll(fds, 3, 20) <= 0) continue;
      while (auto d = board_.endpoint().receive()) {
        parser_.parse_datagram(d->bytes, [&](const hitl::mavlink::Frame& f) {
          if (!f.is<msg::HilSensor>()) return;
          msg::HilActuatorControls a;
          a.time_usec = f.as<msg::HilSensor>().time_usec;
          a.flags = hitl::kVoxl2ActuatorFlags;
          board_.send(a);
          std::lock_guard<std::mutex> lock(mutex_);
          sensor_ns_.push_back(d->rx_time_unix_ns);
        });
      }
      while (auto d = vio_.endpoint().receive())
        vio_parser.parse_datagram(d->bytes, [&](const hitl::mavlink::Frame& f) { vio_frames_ += f.is<msg::Odometry>(); });
      while (auto d = truth_.endpoint().receive())
        truth_parser.parse_datagram(d->bytes, [&](const hitl::mavlink::Frame& f) { truth_frames_ += f.is<msg::Odometry>(); });
    }
  }

  hitl::mavlink::MessageSet set_ = hitl::mavlink::MessageSet::compiled();
  MavlinkPeer board_, vio_, truth_;
  hitl::mavlink::FrameParser parser_;
  std::mutex mutex_;
  std::vector<int64_t> sensor_ns_;
  std::atomic<uint64_t> vio_frames_{0}, truth_frames_{0};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// --- a session watched through its --json status lines ------------------------------------------

/// Samples the usage of `pids` at each `{"type":"status"}` line the session prints; ends after
/// `wall_s` (SIGINT) or when the session ends by itself. Returns the summary (or null).
struct Watched {
  std::vector<json> statuses;
  std::vector<std::vector<Usage>> usage;  ///< per status line, one per pid
  json summary;
  int exit_code = 0;
};

Watched watch(Process& sim, const std::vector<int>& pids, double wall_s) {
  Watched w;
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(wall_s);
  std::size_t seen = 0;
  bool interrupted = false;
  while (sim.running()) {
    if (!interrupted && std::chrono::steady_clock::now() >= until) {
      interrupted = true;
      sim.signal(SIGINT);
    }
    const auto lines = sim.out_lines();
    for (; seen < lines.size(); ++seen) {
      const auto j = json::parse(lines[seen], nullptr, false);
      if (!j.is_object() || j.value("type", "") != "status") continue;
      std::vector<Usage> u;
      for (int pid : pids) u.push_back(usage_of(pid));
      w.statuses.push_back(j);
      w.usage.push_back(std::move(u));
    }
    std::this_thread::sleep_for(5ms);
  }
  w.exit_code = sim.wait(10s);
  const auto lines = sim.out_lines();
  if (!lines.empty()) w.summary = json::parse(lines.back(), nullptr, false);
  return w;
}

std::string port(uint16_t p) { return std::to_string(p); }

std::vector<std::string> sim_args(uint16_t board_port, uint16_t sim_port, uint16_t vio_port, uint16_t clients_port,
                                  const std::vector<std::string>& extra) {
  std::vector<std::string> a{hitl::test::hitl_binary(), "--json", "sim", "-i", "127.0.0.1", "--hil-port", port(board_port),
                             "--local-port", port(sim_port), "--vio-port", port(vio_port), "--clients", port(clients_port)};
  a.insert(a.end(), extra.begin(), extra.end());
  return a;
}

json fail(const std::string& what, const Watched& w) { return json{{"error", what}, {"exit_code", w.exit_code}}; }

// --- 1. real time --------------------------------------------------------------------------------

/// `hitl sim` (or the floor loop when `floor` is set) in real time for `seconds` against the stand-in.
json real_time(double seconds, const std::vector<std::string>& extra, bool floor = false, bool floor_sendmmsg = false) {
  const uint16_t board_port = hitl::test::free_udp_port(), sim_port = hitl::test::free_udp_port(),
                 vio_port = hitl::test::free_udp_port(), clients_port = hitl::test::free_udp_port();
  StandIn board(board_port, sim_port, vio_port, clients_port);
  const std::vector<std::string> args =
      floor ? std::vector<std::string>{std::filesystem::read_symlink("/proc/self/exe").string(), "--floor-loop",
                                       port(board_port), port(sim_port), port(vio_port), port(clients_port),
                                       std::to_string(seconds), floor_sendmmsg ? "sendmmsg" : "sendto"}
            : sim_args(board_port, sim_port, vio_port, clients_port, extra);
  Process sim(args);
  Watched w = watch(sim, {sim.pid()}, seconds + 0.5);
  if (w.statuses.size() < 3) return fail("fewer than 3 status lines: " + sim.err(), w);
  // The window: from the first status line (1 s in: start-up done) to the last.
  const Usage& a = w.usage.front()[0];
  const Usage& b = w.usage.back()[0];
  const double span_s = seconds_between(a, b);
  const double steps = w.statuses.back()["steps"].get<double>() - w.statuses.front()["steps"].get<double>();
  const auto times = board.sensor_times_ns();
  std::vector<double> gaps_us;
  const std::size_t skip = 250;  // the first second
  for (std::size_t i = skip + 1; i + 1 < times.size(); ++i) gaps_us.push_back(static_cast<double>(times[i] - times[i - 1]) / 1000.0);
  const double wall_s = w.summary.value("wall_time_s", 0.0);
  return json{{"seconds", seconds},
              {"cpu_pct_of_core", 100.0 * (b.cpu_s - a.cpu_s) / span_s},
              {"cpu_us_per_tick", 1e6 * (b.cpu_s - a.cpu_s) / std::max(1.0, steps)},
              {"wake_ups_per_tick", static_cast<double>(b.switches - a.switches) / std::max(1.0, steps)},
              {"preemptions_per_tick", static_cast<double>(b.preempted - a.preempted) / std::max(1.0, steps)},
              {"peak_rss_mb", static_cast<double>(b.rss_peak_kb) / 1024.0},
              {"hil_sensor_interarrival", summarize(gaps_us)},
              {"odometry_to_vio_hz", wall_s > 0 ? static_cast<double>(board.vio_frames()) / wall_s : 0.0},
              {"truth_to_client_hz", wall_s > 0 ? static_cast<double>(board.truth_frames()) / wall_s : 0.0},
              {"late_ticks", w.summary.value("late_ticks", json())},
              {"end", w.summary.value("end", json())}};
}

/// Real-time factor and CPU per step of each pid between the first and the last status line.
json lockstep_window(const Watched& w, const std::vector<std::string>& names) {
  if (w.statuses.size() < 2) return json{{"error", "fewer than 2 status lines"}, {"exit_code", w.exit_code}};
  const auto& first = w.statuses.front();
  const auto& last = w.statuses.back();
  const double steps = last["steps"].get<double>() - first["steps"].get<double>();
  const double sim_s = last["sim_time_s"].get<double>() - first["sim_time_s"].get<double>();
  const double span_s = seconds_between(w.usage.front()[0], w.usage.back()[0]);
  json out{{"real_time_factor", sim_s / span_s}, {"steps_per_s", steps / span_s}};
  for (std::size_t i = 0; i < names.size(); ++i) {
    const double cpu_s = w.usage.back()[i].cpu_s - w.usage.front()[i].cpu_s;
    out[names[i] + "_cpu_us_per_step"] = 1e6 * cpu_s / std::max(1.0, steps);
    out[names[i] + "_wake_ups_per_step"] =
        static_cast<double>(w.usage.back()[i].switches - w.usage.front()[i].switches) / std::max(1.0, steps);
  }
  if (w.summary.is_object() && w.summary.contains("lockstep")) out["lockstep"] = w.summary["lockstep"];
  return out;
}

// --- 2. lockstep against the stand-in ------------------------------------------------------------

json lockstep_stand_in(double wall_s, const std::vector<std::string>& extra) {
  const uint16_t board_port = hitl::test::free_udp_port(), sim_port = hitl::test::free_udp_port(),
                 vio_port = hitl::test::free_udp_port(), clients_port = hitl::test::free_udp_port();
  StandIn board(board_port, sim_port, vio_port, clients_port);
  auto args = sim_args(board_port, sim_port, vio_port, clients_port, extra);
  args.insert(args.end(), {"--lockstep", "--speed", "0"});
  Process sim(args);
  return lockstep_window(watch(sim, {sim.pid()}, wall_s + 1.2), {"hitl_sim"});
}

// --- 3. lockstep against hitl target --lockstep -------------------------------------------------

json lockstep_target(double wall_s, const std::vector<std::string>& extra) {
  const uint16_t board_port = hitl::test::free_udp_port(), vio_port = hitl::test::free_udp_port(),
                 sim_port = hitl::test::free_udp_port(), clients_port = hitl::test::free_udp_port();
  Process target({hitl::test::hitl_binary(), "target", "--lockstep", "--bind", "127.0.0.1", "--hil-port", port(board_port),
                  "--gcs-port", "0", "--vio-port", port(vio_port)});
  if (!target.wait_for_stderr("EMULATED", 10s)) return json{{"error", "hitl target did not start: " + target.err()}};
  auto args = sim_args(board_port, sim_port, vio_port, clients_port, extra);
  args.insert(args.end(), {"--lockstep", "--speed", "0"});
  Process sim(args);
  json out = lockstep_window(watch(sim, {sim.pid(), target.pid()}, wall_s + 1.2), {"hitl_sim", "hitl_target"});
  target.signal(SIGINT);
  target.wait(10s);
  return out;
}

// --- output ------------------------------------------------------------------------------------

void print_run(const json& r) {
  for (const char* key : {"floor", "realtime"}) {
    if (!r.contains(key)) continue;
    const auto& x = r[key];
    const char* label = std::string(key) == "floor" ? "floor (no simulator)" : "real time";
    if (x.contains("error")) {
      std::printf("  %s: %s\n", label, x["error"].get<std::string>().c_str());
      continue;
    }
    const auto& g = x["hil_sensor_interarrival"];
    std::printf("  %s %.0f s, VIO %.0f Hz, truth %.0f Hz: CPU %.2f %% of a core (%.1f us/tick, %.2f wake-ups and "
                "%.2f preemptions per tick), peak RSS %.1f MB\n",
                label, x["seconds"].get<double>(), x["odometry_to_vio_hz"].get<double>(), x["truth_to_client_hz"].get<double>(),
                x["cpu_pct_of_core"].get<double>(), x["cpu_us_per_tick"].get<double>(), x["wake_ups_per_tick"].get<double>(),
                x["preemptions_per_tick"].get<double>(), x["peak_rss_mb"].get<double>());
    if (g.contains("std_us"))
      std::printf("    HIL_SENSOR inter-arrival (kernel timestamps, n %d): mean %.1f us, std %.1f us (middle 99.8 %%: %.1f us), "
                  "p99 %.0f us (%+.0f), max %.0f us, %d gaps over 5 ms\n",
                  g["n"].get<int>(), g["mean_us"].get<double>(), g["std_us"].get<double>(),
                  g["std_middle_99_8_us"].get<double>(), g["p99_us"].get<double>(), g["p99_us"].get<double>() - kSensorPeriod_us,
                  g["max_us"].get<double>(), g["gaps_over_period_plus_1ms"].get<int>());
  }
  for (const char* key : {"lockstep_stand_in", "lockstep_target"}) {
    if (!r.contains(key)) continue;
    const auto& x = r[key];
    if (x.contains("error")) {
      std::printf("  %s: %s\n", key, x["error"].dump().c_str());
      continue;
    }
    std::printf("  %s: %.1fx real time (%.0f steps/s), hitl sim %.1f us CPU/step (%.2f wake-ups/step)", key,
                x["real_time_factor"].get<double>(), x["steps_per_s"].get<double>(), x["hitl_sim_cpu_us_per_step"].get<double>(),
                x["hitl_sim_wake_ups_per_step"].get<double>());
    if (x.contains("hitl_target_cpu_us_per_step"))
      std::printf(", hitl target %.1f us CPU/step", x["hitl_target_cpu_us_per_step"].get<double>());
    std::printf("\n");
  }
}

double load_average() {
  std::ifstream f("/proc/loadavg");
  double l = 0;
  f >> l;
  return l;
}

int usage() {
  std::fprintf(stderr,
               "usage: sim_timing_bench [--seconds S] [--lockstep-seconds S] [--runs N] [--json] [--hitl PATH] [--floor-sendmmsg]\n"
               "                        [--only floor|realtime|standin|target] [-- EXTRA hitl sim ARGS...]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 8 && std::string(argv[1]) == "--floor-loop")  // the floor, as a process of its own (real_time)
    return hitl::bench::run_timing_floor({static_cast<uint16_t>(std::atoi(argv[2])), static_cast<uint16_t>(std::atoi(argv[3])),
                                          static_cast<uint16_t>(std::atoi(argv[4])), static_cast<uint16_t>(std::atoi(argv[5]))},
                                         std::atof(argv[6]), std::string(argv[7]) == "sendmmsg");
  double seconds = 20, lockstep_s = 5;
  int runs = 1;
  bool as_json = false, floor_sendmmsg = false;
  std::string only;
  std::vector<std::string> extra;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
    const char* v = nullptr;
    if (a == "--json") as_json = true;
    else if (a == "--floor-sendmmsg") floor_sendmmsg = true;
    else if (a == "--") {
      extra.assign(argv + i + 1, argv + argc);
      break;
    } else if ((a == "--seconds" || a == "--lockstep-seconds" || a == "--runs" || a == "--hitl" || a == "--only") &&
               (v = next()) != nullptr) {
      if (a == "--seconds") seconds = std::atof(v);
      else if (a == "--lockstep-seconds") lockstep_s = std::atof(v);
      else if (a == "--runs") runs = std::max(1, std::atoi(v));
      else if (a == "--only") only = v;
      else setenv("HITL_BINARY_OVERRIDE", v, 1);  // tests/support's hitl_binary() reads it
    } else return usage();
  }
  json out{{"hitl", hitl::test::hitl_binary()},
           {"cpus", std::thread::hardware_concurrency()},
           {"load_average_at_start", load_average()},
           {"extra_sim_args", extra},
           {"runs", json::array()}};
  if (!as_json)
    std::printf("sim_timing_bench: %s, %u CPUs, load average %.2f at start%s\n", out["hitl"].get<std::string>().c_str(),
                std::thread::hardware_concurrency(), load_average(), extra.empty() ? "" : ", extra hitl sim arguments given");
  for (int run = 0; run < runs; ++run) {
    json r;
    if (only.empty() || only == "floor") r["floor"] = real_time(seconds, extra, true, floor_sendmmsg);
    if (only.empty() || only == "realtime") r["realtime"] = real_time(seconds, extra);
    if (only.empty() || only == "standin") r["lockstep_stand_in"] = lockstep_stand_in(lockstep_s, extra);
    if (only.empty() || only == "target") r["lockstep_target"] = lockstep_target(lockstep_s, extra);
    r["load_average_after"] = load_average();
    if (!as_json) {
      std::printf("run %d (load average %.2f after):\n", run + 1, r["load_average_after"].get<double>());
      print_run(r);
      std::fflush(stdout);
    }
    out["runs"].push_back(std::move(r));
  }
  if (as_json) std::printf("%s\n", out.dump().c_str());
  return 0;
}
