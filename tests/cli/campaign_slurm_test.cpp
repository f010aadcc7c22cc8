// hitl campaign slurm against a real Slurm (Debian's slurm-wlm and munge), started by this test on
// this machine with a configuration it writes: one node with the machine's cores, the controller
// and node daemons in the foreground, munge with a key of the test's own. A 6-flight campaign is
// submitted as a job array with collect after it; the merged results must equal a local -j 2 run
// of the same file: the same ids, the same outcomes, the same figures (lockstep). Skipped, saying
// why, when Slurm or munge is not installed or the test is not root (slurmd runs jobs as root here).
#include <gtest/gtest.h>
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "tests/support/json_lines.h"
#include "tests/support/process.h"
#include "tests/support/tools.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;
using nlohmann::json;
namespace fs = std::filesystem;

using test::read_text;

std::string program(const char* name) {
  for (const char* dir : {"/usr/sbin/", "/usr/bin/", "/sbin/", "/bin/"})
    if (::access((std::string(dir) + name).c_str(), X_OK) == 0) return std::string(dir) + name;
  return "";
}

/// A TCP port that was free a moment ago (the kernel's pick).
uint16_t free_tcp_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
  socklen_t len = sizeof a;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
  ::close(fd);
  return ntohs(a.sin_port);
}

/// munged, slurmctld and slurmd of the test's own, stopped at the end.
class Slurm {
 public:
  explicit Slurm(const std::string& dir) : dir_(dir) {
    for (const char* d : {"/state", "/spool", "/log"}) fs::create_directories(dir + d);
    {
      std::ofstream key(dir + "/munge.key", std::ios::binary);
      std::mt19937_64 random(std::random_device{}());
      for (int i = 0; i < 1024; ++i) key.put(static_cast<char>(random() & 0xff));
    }
    fs::permissions(dir + "/munge.key", fs::perms::owner_read | fs::perms::owner_write, fs::perm_options::replace);
    char host[256] = {};
    ::gethostname(host, sizeof host - 1);
    conf_ = dir + "/slurm.conf";
    std::ofstream(conf_) << "ClusterName=hitltest\nSlurmctldHost=" << host << "\nSlurmctldPort=" << free_tcp_port()
                         << "\nSlurmdPort=" << free_tcp_port()
                         << "\nAuthType=auth/munge\nAuthInfo=socket=" << dir << "/munge.sock\nSlurmUser=root\nSlurmdUser=root\n"
                            "ProctrackType=proctrack/linuxproc\nTaskPlugin=task/none\nSelectType=select/cons_tres\n"
                            "SelectTypeParameters=CR_Core\nSchedulerType=sched/backfill\nMpiDefault=none\nReturnToService=2\n"
                            "StateSaveLocation=" << dir << "/state\nSlurmdSpoolDir=" << dir << "/spool\nSlurmctldPidFile=" << dir
                         << "/slurmctld.pid\nSlurmdPidFile=" << dir << "/slurmd.pid\nSlurmctldLogFile=" << dir
                         << "/log/slurmctld.log\nSlurmdLogFile=" << dir << "/log/slurmd.log\n"
                            "AccountingStorageType=accounting_storage/none\nJobCompType=jobcomp/none\n"
                            "JobAcctGatherType=jobacct_gather/none\nNodeName=" << host << " CPUs="
                         << std::max(1u, std::thread::hardware_concurrency())
                         << " State=UNKNOWN\nPartitionName=hitl Nodes=ALL Default=YES MaxTime=INFINITE State=UP\n";
    ::setenv("SLURM_CONF", conf_.c_str(), 1);
    munge_ = std::make_unique<test::Process>(std::vector<std::string>{
        program("munged"), "-F", "--force", "--socket=" + dir + "/munge.sock", "--key-file=" + dir + "/munge.key",
        "--log-file=" + dir + "/log/munged.log", "--pid-file=" + dir + "/munged.pid", "--seed-file=" + dir + "/munge.seed"});
    for (int i = 0; i < 50 && !fs::exists(dir + "/munge.sock"); ++i) std::this_thread::sleep_for(100ms);
    ctld_ = std::make_unique<test::Process>(std::vector<std::string>{program("slurmctld"), "-D", "-f", conf_});
    slurmd_ = std::make_unique<test::Process>(std::vector<std::string>{program("slurmd"), "-D", "-f", conf_});
  }
  ~Slurm() {
    slurmd_.reset();
    ctld_.reset();
    munge_.reset();
    ::unsetenv("SLURM_CONF");
  }
  /// Until the node is idle (sinfo), up to `limit`.
  bool ready(std::chrono::seconds limit) {
    const auto end = std::chrono::steady_clock::now() + limit;
    while (std::chrono::steady_clock::now() < end) {
      test::Process sinfo({program("sinfo"), "-h", "-o", "%T"});
      sinfo.wait(10s);
      if (sinfo.out().find("idle") != std::string::npos) return true;
      std::this_thread::sleep_for(500ms);
    }
    return false;
  }
  std::string logs() const { return read_text(dir_ + "/log/slurmctld.log") + read_text(dir_ + "/log/slurmd.log"); }

 private:
  std::string dir_, conf_;
  std::unique_ptr<test::Process> munge_, ctld_, slurmd_;
};

json by_id(const json& summary) {
  json out = json::object();
  for (const auto& r : summary["results"]) out[r["id"].get<std::string>()] = r;
  return out;
}

TEST(CampaignSlurm, AJobArrayOnARealSlurmGivesWhatALocalRunGives) {
  if (::geteuid() != 0) GTEST_SKIP() << "not root: slurmd here runs the jobs as root (CI runs as root)";
  for (const char* p : {"munged", "slurmctld", "slurmd", "sbatch", "sinfo"})
    if (program(p).empty()) GTEST_SKIP() << p << " is not installed: scripts/install-deps.sh --test installs slurm-wlm and munge";
  const std::string dir = test::temp_dir();
  Slurm slurm(dir);
  ASSERT_TRUE(slurm.ready(60s)) << "Slurm did not come up:\n" << slurm.logs();

  std::ofstream(dir + "/hover.json")
      << R"({"waypoints": [{"t": 0, "x": 0, "y": 0, "z": 2, "yaw": 0}, {"t": 3, "x": 0, "y": 0, "z": 2, "yaw": 0}]})";
  const std::string file = dir + "/six.toml";
  std::ofstream(file) << "[campaign]\nname = \"six\"\ntime_limit_s = 120\n[matrix]\ntrajectories = [\"hover.json\"]\n"
                         "seeds = [1, 2, 3]\n[faults]\nnone = []\ngps-loss = [\"gps-loss@2+2\"]\n"
                         "[criteria]\ndisarmed = { figure = \"stack.armed\", equals = false }\n"
                         "tight = { figure = \"trajectory.max_m\", max = 0.05 }\n";  // some flights fail it

  auto submitted = test::run_hitl({"--json", "campaign", "slurm", file, "--out", dir + "/slurm-results", "--no-history"}, 60s);
  ASSERT_EQ(submitted.exit_code, 0) << submitted.out << submitted.err;
  const auto s = test::last_json_line(submitted.out);
  EXPECT_EQ(s["flights"], 6);
  const std::string summary_file = dir + "/slurm-results/summary.json";
  const auto end = std::chrono::steady_clock::now() + 300s;
  while (!fs::exists(summary_file) && std::chrono::steady_clock::now() < end) std::this_thread::sleep_for(500ms);
  ASSERT_TRUE(fs::exists(summary_file)) << "collect did not run:\n" << slurm.logs();
  std::this_thread::sleep_for(500ms);  // collect writes junit.xml beside it
  EXPECT_TRUE(fs::exists(dir + "/slurm-results/junit.xml"));
  for (int i = 0; i < 6; ++i) EXPECT_TRUE(fs::exists(dir + "/slurm-results/slurm/flight-" + std::to_string(i) + ".out")) << i;

  auto local = test::run_hitl({"campaign", "run", file, "-j", "2", "--out", dir + "/local-results", "--no-history"}, 300s);
  EXPECT_LE(local.exit_code, 1) << local.err;
  const auto slurm_summary = json::parse(read_text(summary_file));
  const auto local_summary = json::parse(read_text(dir + "/local-results/summary.json"));
  EXPECT_EQ(slurm_summary["flights"], 6);
  EXPECT_EQ(slurm_summary["missing"], 0) << slurm_summary.dump();
  const json a = by_id(slurm_summary), b = by_id(local_summary);
  ASSERT_EQ(a.size(), 6u);
  for (const auto& [id, flight] : a.items()) {
    ASSERT_TRUE(b.contains(id)) << id;
    EXPECT_EQ(flight["outcome"], b[id]["outcome"]) << id;
    EXPECT_EQ(flight["failures"], b[id]["failures"]) << id;
    const auto fa = json::parse(read_text(dir + "/slurm-results/flights/" + id + "/summary.json"));
    const auto fb = json::parse(read_text(dir + "/local-results/flights/" + id + "/summary.json"));
    for (const char* path : {"/trajectory/rms_m", "/trajectory/max_m", "/sim_time_s", "/steps", "/landing/touchdowns",
                             "/landing/max_rebound_m", "/position_ned_m"})
      EXPECT_EQ(fa.at(json::json_pointer(path)), fb.at(json::json_pointer(path))) << id << " " << path;
  }
}

}  // namespace
}  // namespace hitl
