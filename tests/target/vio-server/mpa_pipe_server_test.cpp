// hitl's MPA pipe server against a client that connects as libmodal_pipe's pipe_client does:
// the directory, info file and request FIFO; a data FIFO per request; whole records; refused
// requests; disconnects noticed through inotify; a stale directory; cleanup.
#include "target/vio-server/mpa_pipe_server.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>

#include "tests/support/process.h"
#include "tests/target/vio-server/mpa_client.h"

namespace hitl::vio {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

PipeInfo test_info(int size_bytes = 64 * 1024) { return {"test_pipe", "test_record_t", "mpa-test", size_bytes}; }

/// Services the server from a thread, as the vio-server's loop does, while a test client connects.
class Serving {
 public:
  explicit Serving(MpaPipeServer& server) : server_(server), thread_([this] {
    while (!stop_) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        server_.service();
      }
      std::this_thread::sleep_for(1ms);
    }
  }) {}
  ~Serving() {
    stop_ = true;
    thread_.join();
  }
  template <class F>
  auto locked(F f) {
    std::lock_guard<std::mutex> lock(mutex_);
    return f(server_);
  }
  /// Waits until `pred(server)` holds.
  template <class F>
  bool wait_for(F pred, std::chrono::milliseconds timeout = 3s) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
      if (locked(pred)) return true;
      std::this_thread::sleep_for(2ms);
    }
    return false;
  }

 private:
  MpaPipeServer& server_;
  std::atomic<bool> stop_{false};
  std::mutex mutex_;
  std::thread thread_;
};

std::unique_ptr<MpaPipeServer> make(const std::string& base, PipeInfo info = test_info()) {
  auto s = MpaPipeServer::create(base, info);
  EXPECT_TRUE(s.ok()) << (s.ok() ? "" : s.error().message);
  return s.ok() ? std::move(s.value()) : nullptr;
}

TEST(MpaPipeServer, MakesTheDirectoryInfoFileAndRequestFifo) {
  const std::string base = test::temp_dir() + "/run/mpa";  // made with its parents
  auto server = make(base);
  ASSERT_TRUE(server);
  const std::string dir = base + "/test_pipe/";
  EXPECT_EQ(server->location(), dir);
  struct stat st{};
  ASSERT_EQ(::stat(dir.c_str(), &st), 0);
  EXPECT_TRUE(S_ISDIR(st.st_mode));
  ASSERT_EQ(::stat((dir + "request").c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
  EXPECT_FALSE(fs::exists(dir + "control"));  // none: clients treat ENOENT as "no control pipe"

  std::ifstream in(dir + "info");
  const auto info = nlohmann::json::parse(in);
  EXPECT_EQ(info["name"], "test_pipe");
  EXPECT_EQ(info["location"], dir);
  EXPECT_EQ(info["type"], "test_record_t");
  EXPECT_EQ(info["server_name"], "mpa-test");
  EXPECT_EQ(info["size_bytes"], 64 * 1024);
  EXPECT_EQ(info["server_pid"], ::getpid());

  server.reset();
  EXPECT_FALSE(fs::exists(dir)) << "the pipe's directory is removed when the server closes";
}

TEST(MpaPipeServer, AClientGetsItsOwnFifoAndWholeRecords) {
  const std::string base = test::temp_dir();
  auto server = make(base);
  ASSERT_TRUE(server);
  Serving serving(*server);
  std::string error;
  auto client = test::MpaClient::connect(server->location(), "voxl-vision-hub", error);
  ASSERT_TRUE(client.connected()) << error;
  // The FIFO is named by the request: "voxl-vision-hub" and 8 digits.
  const std::string fifo = fs::path(client.fifo_path()).filename().string();
  EXPECT_EQ(fifo.size(), 15u + 8u);
  EXPECT_EQ(fifo.rfind("voxl-vision-hub", 0), 0u);
  ASSERT_TRUE(serving.wait_for([](auto& s) { return s.clients() == 1 && !s.connecting(); }));
  EXPECT_EQ(::fcntl(client.fd(), F_GETPIPE_SZ), 64 * 1024);  // info.size_bytes

  std::array<uint8_t, 324> record{};
  for (int i = 0; i < 50; ++i) {
    record.fill(static_cast<uint8_t>(i));
    serving.locked([&](auto& s) { s.write(record); return 0; });
  }
  for (int i = 0; i < 50; ++i) {
    std::array<uint8_t, 324> got{};
    ASSERT_TRUE(client.read_exact(got.data(), got.size(), 2s)) << i;
    EXPECT_EQ(got.front(), i);
    EXPECT_EQ(got.back(), i);
  }
  EXPECT_EQ(serving.locked([](auto& s) { return s.counters().records_written; }), 50u);
  EXPECT_EQ(serving.locked([](auto& s) { return s.counters().clients_accepted; }), 1u);
}

TEST(MpaPipeServer, TwoClientsEachGetEveryRecord) {
  const std::string base = test::temp_dir();
  auto server = make(base);
  ASSERT_TRUE(server);
  Serving serving(*server);
  std::string e1, e2;
  auto a = test::MpaClient::connect(server->location(), "client-a", e1);
  auto b = test::MpaClient::connect(server->location(), "client-b", e2);
  ASSERT_TRUE(a.connected()) << e1;
  ASSERT_TRUE(b.connected()) << e2;
  ASSERT_TRUE(serving.wait_for([](auto& s) { return s.clients() == 2 && !s.connecting(); }));
  const std::array<uint8_t, 8> record{1, 2, 3, 4, 5, 6, 7, 8};
  serving.locked([&](auto& s) { s.write(record); return 0; });
  std::array<uint8_t, 8> got{};
  ASSERT_TRUE(a.read_exact(got.data(), got.size(), 2s));
  EXPECT_EQ(got, record);
  ASSERT_TRUE(b.read_exact(got.data(), got.size(), 2s));
  EXPECT_EQ(got, record);
}

TEST(MpaPipeServer, AClientThatClosesIsDroppedAndItsFifoRemoved) {
  const std::string base = test::temp_dir();
  auto server = make(base);
  ASSERT_TRUE(server);
  Serving serving(*server);
  std::string error;
  auto client = test::MpaClient::connect(server->location(), "leaver", error);
  ASSERT_TRUE(client.connected()) << error;
  ASSERT_TRUE(serving.wait_for([](auto& s) { return s.clients() == 1 && !s.connecting(); }));
  const std::string fifo = client.fifo_path();
  client.close();  // no data flowing: inotify's IN_CLOSE_NOWRITE is how the server learns of it
  EXPECT_TRUE(serving.wait_for([](auto& s) { return s.clients() == 0; }));
  EXPECT_FALSE(fs::exists(fifo));
  // The same name may connect again.
  auto again = test::MpaClient::connect(server->location(), "leaver", error);
  EXPECT_TRUE(again.connected()) << error;
}

TEST(MpaPipeServer, AClientThatFallsBehindLosesRecordsNotAlignment) {
  const std::string base = test::temp_dir();
  auto server = make(base, test_info(4096));  // the smallest pipe: 4096 bytes
  ASSERT_TRUE(server);
  Serving serving(*server);
  std::string error;
  auto client = test::MpaClient::connect(server->location(), "slow", error);
  ASSERT_TRUE(client.connected()) << error;
  ASSERT_TRUE(serving.wait_for([](auto& s) { return s.clients() == 1 && !s.connecting(); }));
  std::array<uint8_t, 1000> record{};
  for (int i = 0; i < 10; ++i) {  // 4 fit, 6 are dropped
    record.fill(static_cast<uint8_t>(i));
    serving.locked([&](auto& s) { s.write(record); return 0; });
  }
  EXPECT_EQ(serving.locked([](auto& s) { return s.counters().records_written; }), 4u);
  EXPECT_EQ(serving.locked([](auto& s) { return s.counters().records_dropped; }), 6u);
  for (int i = 0; i < 4; ++i) {
    std::array<uint8_t, 1000> got{};
    ASSERT_TRUE(client.read_exact(got.data(), got.size(), 2s));
    EXPECT_EQ(got.front(), i);
    EXPECT_EQ(got.back(), i);
  }
  EXPECT_EQ(client.queued(), 0);
}

TEST(MpaPipeServer, RefusesRequestsThatCouldEscapeOrCollide) {
  const std::string base = test::temp_dir();
  auto server = make(base);
  ASSERT_TRUE(server);
  const std::string dir = server->location();
  auto request = [&](const std::string& bytes) {
    const int fd = ::open((dir + "request").c_str(), O_WRONLY | O_NONBLOCK);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(::write(fd, bytes.data(), bytes.size()), static_cast<ssize_t>(bytes.size()));
    ::close(fd);
    server->service();
  };
  request(std::string("../../escape") + '\0');
  request(std::string("info") + '\0');
  request(std::string("request") + '\0');
  request(std::string("..") + '\0');
  request(std::string(40, 'a') + '\0');
  request(std::string("new\nline") + '\0');
  request(std::string("ctl\x01") + '\0');
  EXPECT_EQ(server->counters().requests_rejected, 7u);
  EXPECT_FALSE(fs::exists(fs::path(base).parent_path() / "escape"));
  const auto events = server->take_events();
  ASSERT_EQ(events.size(), 7u);
  EXPECT_NE(events[0].find("'/'"), std::string::npos) << events[0];
  EXPECT_NE(events[1].find("reserved"), std::string::npos) << events[1];
  EXPECT_NE(events[4].find("longer than 31"), std::string::npos) << events[4];
  // Two requests in one write, the second a duplicate of the first.
  request(std::string("twin") + '\0' + "twin" + '\0');
  EXPECT_EQ(server->counters().requests_rejected, 8u);
  EXPECT_EQ(server->clients(), 1);
  EXPECT_NE(server->check_client_name("twin").find("connected"), std::string::npos);
}

TEST(MpaPipeServer, AbandonsARequestWhoseClientNeverOpens) {
  const std::string base = test::temp_dir();
  auto server = make(base);
  ASSERT_TRUE(server);
  const int fd = ::open((server->location() + "request").c_str(), O_WRONLY | O_NONBLOCK);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::write(fd, "ghost12345678", 14), 14);
  ::close(fd);
  server->service();
  EXPECT_TRUE(server->connecting());
  EXPECT_TRUE(fs::exists(server->location() + "ghost12345678"));
  const auto deadline = std::chrono::steady_clock::now() + kClientOpenTimeout + 3s;
  while (server->connecting() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(20ms);
    server->service();
  }
  EXPECT_FALSE(server->connecting());
  EXPECT_EQ(server->clients(), 0);
  EXPECT_FALSE(fs::exists(server->location() + "ghost12345678"));
}

TEST(MpaPipeServer, ReplacesAStaleDirectoryButNotALiveServersOne) {
  const std::string base = test::temp_dir();
  const std::string dir = base + "/test_pipe/";
  // A dead server's leftovers: an info file naming an exited process and an old client FIFO.
  const pid_t dead = ::fork();
  if (dead == 0) std::_Exit(0);
  ::waitpid(dead, nullptr, 0);
  fs::create_directories(dir);
  std::ofstream(dir + "info") << nlohmann::json{{"server_pid", dead}}.dump();
  ASSERT_EQ(::mkfifo((dir + "old-client00000001").c_str(), 0666), 0);
  {
    auto server = make(base);
    ASSERT_TRUE(server);
    EXPECT_FALSE(fs::exists(dir + "old-client00000001"));
    const auto events = server->take_events();
    ASSERT_FALSE(events.empty());
    EXPECT_NE(events[0].find("stale"), std::string::npos);
  }
  // A live process's pipe is refused, and left alone.
  fs::create_directories(dir);
  std::ofstream(dir + "info") << nlohmann::json{{"server_pid", 1}}.dump();  // init: alive
  auto refused = MpaPipeServer::create(base, test_info());
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("already served by process 1"), std::string::npos) << refused.error().message;
  EXPECT_TRUE(fs::exists(dir + "info"));
}

TEST(MpaPipeServer, RefusesBadNamesAndRelativeBases) {
  EXPECT_FALSE(MpaPipeServer::create(test::temp_dir(), {"a/b", "t", "s", 4096}).ok());
  EXPECT_FALSE(MpaPipeServer::create(test::temp_dir(), {"", "t", "s", 4096}).ok());
  EXPECT_FALSE(MpaPipeServer::create("run/mpa", test_info()).ok());
  auto unwritable = MpaPipeServer::create("/proc/hitl-no-such-dir", test_info());
  ASSERT_FALSE(unwritable.ok());
  EXPECT_NE(unwritable.error().message.find("cannot create the MPA directory"), std::string::npos);
}

}  // namespace
}  // namespace hitl::vio
