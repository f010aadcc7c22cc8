// hitl bridge under load, measured from outside over loopback (issue 27): a stand-in board streams
// ATTITUDE and HIGHRES_IMU (each carrying its index; the send time is kept here) to the bridge's
// board port, flat out or paced, while 1 / 10 / 100 UDP clients on the bridge's client port count
// what reaches them. Per run: per-client rate, loss split by where it happened (before the bridge
// took the frames in; after, counted by the bridge; in the clients' own sockets; unexplained),
// latency p50/p99/max (board send to the kernel's arrival time at the client), the bridge's CPU. One JSON object per run on stdout, a table on stderr.
//
//   build/bench/bridge/bridge_load_bench [--hitl PATH] [--seconds S] [--clients 1,10,100] [--rates 0,1000]
//                                        [--peer CMD] [--lossless] [--bridge-args "--queue-ms 500"]
//
// --rates: board frames per second, 0 = flat out. --hitl runs another build's binary (main's), so
// the same command measures before and after. --peer CMD runs a mavlink-router beside it in the
// same run, each load right after hitl's: CMD gets mavlink-routerd's arguments appended (`-t 0`,
// `-e 127.0.0.1:PORT` per client, the board side `127.0.0.1:PORT` in server mode), e.g.
// `--peer /root/peers/mavlink-router/build/src/mavlink-routerd`. --lossless adds one more
// listener behind hitl's `--endpoint udp:127.0.0.1:PORT?lossless` and reports what it lost after
// intake; --bridge-args adds options to `hitl bridge`. Both routers' intake is read the same way: the kernel's drop count of the socket on the
// board side (/proc/net/udp), so "lost after intake" means the same for both. Bounded: each run
// lasts S seconds plus ~4 s.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/epoll.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/messages.h"
#include "tests/support/loopback.h"
#include "tests/support/process.h"

namespace {

using namespace std::chrono_literals;
namespace msg = hitl::mavlink::msg;
using hitl::test::loopback_address;

int64_t now_ns() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return int64_t{t.tv_sec} * 1'000'000'000 + t.tv_nsec;
}

/// CLOCK_REALTIME, the clock of the kernel's receive timestamps (SO_TIMESTAMPNS).
int64_t wall_ns() {
  timespec t{};
  clock_gettime(CLOCK_REALTIME, &t);
  return int64_t{t.tv_sec} * 1'000'000'000 + t.tv_nsec;
}

/// A UDP socket on 127.0.0.1:port (0: ephemeral) with a large receive buffer, SO_RXQ_OVFL and
/// kernel receive timestamps (the latency is the kernel's arrival time at the client, so a busy
/// reader here does not add to it).
int open_socket(uint16_t port) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK, 0);
  const int bytes = 8 << 20, on = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &bytes, sizeof bytes);
  ::setsockopt(fd, SOL_SOCKET, SO_RXQ_OVFL, &on, sizeof on);
  ::setsockopt(fd, SOL_SOCKET, SO_TIMESTAMPNS, &on, sizeof on);
  const auto a = loopback_address(port);
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0) {
    std::perror("bind");
    std::exit(1);
  }
  return fd;
}

uint16_t port_of(int fd) {
  sockaddr_in a{};
  socklen_t len = sizeof a;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
  return ntohs(a.sin_port);
}

/// utime + stime of a process, in seconds.
double cpu_s(int pid) {
  std::ifstream f("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  std::istringstream in(text.substr(text.rfind(')') + 2));
  std::string field;
  unsigned long long utime = 0, stime = 0;
  for (int i = 3; i <= 15 && in >> field; ++i) {
    if (i == 14) utime = std::stoull(field);
    if (i == 15) stime = std::stoull(field);
  }
  return static_cast<double>(utime + stime) / static_cast<double>(sysconf(_SC_CLK_TCK));
}

struct Client {
  int fd = -1;
  uint64_t received = 0;
  uint32_t kernel_drops = 0;  ///< SO_RXQ_OVFL: what this client's own socket dropped
};

struct Run {
  int clients = 1;
  double rate_hz = 0;  ///< 0: flat out
  double seconds = 3;
  std::string peer;    ///< a mavlink-routerd command instead of hitl ("": hitl)
  bool lossless = false;  ///< hitl: one more listener behind --endpoint udp:...?lossless
  std::string hitl_args;  ///< more `hitl bridge` options (--bridge-args "--queue-ms 500")
};

/// The kernel's drop count of the UDP socket bound to `port` (any address), from /proc/net/udp.
uint64_t proc_udp_drops(uint16_t port) {
  std::ifstream f("/proc/net/udp");
  std::string line;
  std::getline(f, line);  // header
  char want[8];
  std::snprintf(want, sizeof want, ":%04X", port);
  while (std::getline(f, line)) {
    std::istringstream in(line);
    std::string sl, local;
    in >> sl >> local;
    if (local.size() < 5 || local.substr(local.size() - 5) != want) continue;
    std::string field, drops;
    for (int i = 0; i < 10 && in >> field;) ++i;  // rem st tx:rx tr:when retrnsmt uid timeout inode ref pointer
    in >> drops;
    return drops.empty() ? 0 : std::stoull(drops);
  }
  return 0;
}

std::vector<std::string> split_words(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

double percentile(std::vector<int64_t>& v, double p) {
  if (v.empty()) return 0;
  const auto k = static_cast<std::size_t>(p * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return static_cast<double>(v[k]) / 1000.0;
}

/// The last JSON object of the bridge's stdout whose type is `type`.
nlohmann::json last_of(const std::vector<std::string>& lines, const std::string& type) {
  for (auto it = lines.rbegin(); it != lines.rend(); ++it) {
    auto j = nlohmann::json::parse(*it, nullptr, false);
    if (!j.is_discarded() && j.value("type", "") == type) return j;
  }
  return nlohmann::json::object();
}

uint64_t field_or(const nlohmann::json& j, const char* key, uint64_t fallback = 0) {
  return j.is_object() && j.contains(key) && j[key].is_number() ? j[key].get<uint64_t>() : fallback;
}

nlohmann::json run_once(const std::string& hitl, const Run& run) {
  const int board_fd = open_socket(0);
  const uint16_t board_port = port_of(board_fd);
  const uint16_t local_port = hitl::test::free_udp_port(), clients_port = hitl::test::free_udp_port();
  const bool is_peer = !run.peer.empty();
  std::vector<Client> clients(static_cast<std::size_t>(run.clients));
  for (auto& c : clients) c.fd = open_socket(0);
  Client recorder;  // --lossless: behind hitl's ?lossless endpoint
  if (run.lossless && !is_peer) recorder.fd = open_socket(0);
  std::vector<std::string> argv;
  if (is_peer) {
    argv = split_words(run.peer);
    argv.insert(argv.end(), {"-t", "0"});
    for (const auto& c : clients) argv.insert(argv.end(), {"-e", "127.0.0.1:" + std::to_string(port_of(c.fd))});
    argv.push_back("127.0.0.1:" + std::to_string(local_port));
  } else {
    argv = {hitl, "--json", "bridge", "-i", "127.0.0.1", "--port", std::to_string(board_port), "--local-port",
            std::to_string(local_port), "--clients", std::to_string(clients_port), "--duration",
            std::to_string(static_cast<int>(run.seconds) + 30)};
    if (recorder.fd >= 0) argv.insert(argv.end(), {"--endpoint", "udp:127.0.0.1:" + std::to_string(port_of(recorder.fd)) + "?lossless"});
    for (const auto& w : split_words(run.hitl_args)) argv.push_back(w);
  }
  hitl::test::Process bridge(argv);
  if (!is_peer && !bridge.wait_for_stderr("clients on", 10s)) {
    std::fprintf(stderr, "the bridge did not start: %s\n", bridge.err().c_str());
    std::exit(1);
  }
  if (is_peer) std::this_thread::sleep_for(500ms);  // mavlink-routerd says nothing when it is ready
  const int ep = ::epoll_create1(0);
  hitl::mavlink::FrameBuffer buf;
  for (std::size_t i = 0; i <= clients.size(); ++i) {
    if (i == clients.size() && recorder.fd < 0) break;
    Client& c = i < clients.size() ? clients[i] : recorder;
    epoll_event ev{};
    ev.events = EPOLLIN;
    ev.data.u64 = i;
    ::epoll_ctl(ep, EPOLL_CTL_ADD, c.fd, &ev);
    if (is_peer || i == clients.size()) continue;  // mavlink-router sends to its -e endpoints unasked
    hitl::mavlink::FrameEncoder enc(200, static_cast<uint8_t>(1 + i));
    const std::size_t n = enc.encode(msg::Heartbeat{}, buf);
    const auto to = loopback_address(clients_port);
    ::sendto(c.fd, buf.data(), n, 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
  }
  std::this_thread::sleep_for(500ms);  // every client known to the bridge before the stream

  const std::size_t capacity = run.rate_hz > 0 ? static_cast<std::size_t>(run.rate_hz * run.seconds) + 16 : 20'000'000;
  std::vector<int64_t> sent_at(capacity, 0);
  std::atomic<bool> sending{true};
  std::atomic<int64_t> stop_ns{0};
  std::vector<int64_t> latencies_ns;
  latencies_ns.reserve(4'000'000);
  std::thread receiver([&] {
    epoll_event events[128];
    uint8_t data[2048];
    alignas(cmsghdr) char control[CMSG_SPACE(sizeof(uint32_t)) + CMSG_SPACE(sizeof(timespec))];
    int64_t idle_since = now_ns(), next_heartbeat = now_ns();
    const auto clients_at = loopback_address(clients_port);
    for (;;) {
      if (!is_peer && now_ns() >= next_heartbeat) {  // clients say they are there, as MAVLink clients do (the bridge forgets one after 10 s)
        next_heartbeat += 2'000'000'000;
        hitl::mavlink::FrameBuffer hb;
        for (std::size_t i = 0; i < clients.size(); ++i) {
          hitl::mavlink::FrameEncoder enc(200, static_cast<uint8_t>(1 + i));
          const std::size_t len = enc.encode(msg::Heartbeat{}, hb);
          ::sendto(clients[i].fd, hb.data(), len, 0, reinterpret_cast<const sockaddr*>(&clients_at), sizeof clients_at);
        }
      }
      const int n = ::epoll_wait(ep, events, 128, 50);
      if (n <= 0) {
        if (!sending && now_ns() - idle_since > 1'000'000'000) return;  // drained: a second of silence
        continue;
      }
      if (!sending && now_ns() - stop_ns > 30'000'000'000) return;  // bounded, however slow the drain
      idle_since = now_ns();
      for (int e = 0; e < n; ++e) {
        const auto which = events[e].data.u64;
        Client& c = which < clients.size() ? clients[which] : recorder;
        const bool timed = which < clients.size();  // the recorder's copies are counted, not timed
        for (;;) {
          iovec iov{data, sizeof data};
          msghdr m{};
          m.msg_iov = &iov;
          m.msg_iovlen = 1;
          m.msg_control = control;
          m.msg_controllen = sizeof control;
          const ssize_t len = ::recvmsg(c.fd, &m, MSG_DONTWAIT);
          if (len < 0) break;
          int64_t arrived_ns = 0;
          for (cmsghdr* cm = CMSG_FIRSTHDR(&m); cm != nullptr; cm = CMSG_NXTHDR(&m, cm)) {
            if (cm->cmsg_level == SOL_SOCKET && cm->cmsg_type == SO_RXQ_OVFL) std::memcpy(&c.kernel_drops, CMSG_DATA(cm), sizeof(uint32_t));
            if (cm->cmsg_level == SOL_SOCKET && cm->cmsg_type == SCM_TIMESTAMPNS) {
              timespec ts{};
              std::memcpy(&ts, CMSG_DATA(cm), sizeof ts);
              arrived_ns = int64_t{ts.tv_sec} * 1'000'000'000 + ts.tv_nsec;
            }
          }
          if (arrived_ns == 0) arrived_ns = wall_ns();
          if (len < 14 || data[0] != 0xFD) continue;
          const uint32_t id = data[7] | (data[8] << 8) | (data[9] << 16);
          if (id != msg::Attitude::kId && id != msg::HighresImu::kId) continue;
          uint32_t index = 0;
          std::memcpy(&index, data + 10, sizeof index);  // time_boot_ms / the low half of time_usec
          ++c.received;
          if (timed && index < capacity && sent_at[index] != 0 && latencies_ns.size() < latencies_ns.capacity())
            latencies_ns.push_back(arrived_ns - sent_at[index]);
        }
      }
    }
  });

  const double cpu_before = cpu_s(bridge.pid());
  const int64_t start = now_ns();
  const int64_t end = start + static_cast<int64_t>(run.seconds * 1e9);
  const int64_t period = run.rate_hz > 0 ? static_cast<int64_t>(1e9 / run.rate_hz) : 0;
  hitl::mavlink::FrameEncoder board(1, 1);
  const auto to = loopback_address(local_port);
  uint64_t sent = 0, send_refused = 0;
  for (int64_t next = start; sent < capacity; next += period) {
    const int64_t t = now_ns();
    if (t >= end) break;
    if (period > 0 && t < next) {
      const timespec ts{static_cast<time_t>(next / 1'000'000'000), static_cast<long>(next % 1'000'000'000)};
      clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr);
    }
    std::size_t n = 0;
    const auto index = static_cast<uint32_t>(sent);
    if (sent % 2 == 0) {
      msg::Attitude a{};
      a.time_boot_ms = index;
      a.yawspeed = 1.0f;  // the last field non-zero: the payload is never truncated below the index
      n = board.encode(a, buf);
    } else {
      msg::HighresImu h{};
      h.time_usec = index;
      h.id = 1;
      n = board.encode(h, buf);
    }
    sent_at[sent] = wall_ns();
    if (::sendto(board_fd, buf.data(), n, 0, reinterpret_cast<const sockaddr*>(&to), sizeof to) < 0) {
      ++send_refused;  // our own socket full: not sent, so not counted as sent
      sent_at[sent] = 0;
      pollfd p{board_fd, POLLOUT, 0};
      ::poll(&p, 1, 10);
      continue;
    }
    ++sent;
  }
  const double send_s = static_cast<double>(now_ns() - start) / 1e9;
  stop_ns = now_ns();
  sending = false;
  receiver.join();
  const double wall_s = static_cast<double>(now_ns() - start) / 1e9;
  const double cpu = cpu_s(bridge.pid()) - cpu_before;
  const double drain_s = wall_s - send_s;
  std::this_thread::sleep_for(1200ms);  // one more health report after the drain
  const auto status = last_of(bridge.out_lines(), "status");
  const uint64_t kernel_drops_board_side = proc_udp_drops(local_port);  // before it closes
  bridge.signal(SIGINT);
  bridge.wait(10s);

  nlohmann::json links = status.value("links", nlohmann::json::array());
  nlohmann::json board_link = links.size() > 0 ? links[0] : nlohmann::json::object();
  nlohmann::json clients_link = links.size() > 1 ? links[1] : nlohmann::json::object();
  // Taken in: what the board side's socket did not drop (the same measure for hitl and the peer;
  // hitl's own count is hitl_taken_in).
  const uint64_t taken_in = sent - std::min(sent, kernel_drops_board_side);
  const uint64_t hitl_taken_in = field_or(board_link, "packets_in");
  uint64_t min_rx = UINT64_MAX, max_rx = 0, sum_rx = 0, client_kernel = 0;
  for (const auto& c : clients) {
    min_rx = std::min(min_rx, c.received);
    max_rx = std::max(max_rx, c.received);
    sum_rx += c.received;
    client_kernel += c.kernel_drops;
    ::close(c.fd);
  }
  const uint64_t recorder_lost = recorder.fd >= 0 ? taken_in - std::min(taken_in, recorder.received + recorder.kernel_drops) : 0;
  if (recorder.fd >= 0) ::close(recorder.fd);
  ::close(ep);
  ::close(board_fd);
  const double n_clients = static_cast<double>(clients.size());
  const uint64_t lost_after = taken_in * clients.size() - std::min(taken_in * clients.size(), sum_rx);
  const uint64_t bridge_counted = field_or(clients_link, "dropped") + field_or(clients_link, "send_errors");
  uint64_t drops_reported = 0;  // what the router said it dropped: before intake and after
  if (!is_peer) {
    drops_reported = field_or(status, "kernel_rx_drops");
    for (const auto& l : links) drops_reported += field_or(l, "dropped") + (l.value("name", "") == "board" ? 0 : field_or(l, "kernel_rx_drops"));
  }
  nlohmann::json j = {
      {"router", is_peer ? "peer: " + run.peer : "hitl"},
      {"kernel_drops_board_side", kernel_drops_board_side},
      {"drops_reported", is_peer ? nlohmann::json(nullptr) : nlohmann::json(drops_reported)},
      {"lossless_lost_after", recorder.fd >= 0 ? nlohmann::json(recorder_lost) : nlohmann::json(nullptr)},
      {"lossless_received", recorder.fd >= 0 ? nlohmann::json(recorder.received) : nlohmann::json(nullptr)},
      {"hitl_taken_in", hitl_taken_in},
      {"clients", run.clients},
      {"board_rate_hz", run.rate_hz > 0 ? nlohmann::json(run.rate_hz) : nlohmann::json("flat out")},
      {"seconds", send_s},
      {"board_sent", sent},
      {"board_send_refused_here", send_refused},
      {"bridge_taken_in", taken_in},
      {"lost_before_bridge", sent - std::min(sent, taken_in)},
      {"bridge_kernel_rx_drops", status.contains("kernel_rx_drops") ? status["kernel_rx_drops"] : nlohmann::json(nullptr)},
      {"bridge_loss_reported", status.value("loss", nlohmann::json::object())},
      {"per_client_rx_mean", sum_rx / clients.size()},
      {"per_client_rx_min", min_rx},
      {"per_client_rate_hz", static_cast<double>(sum_rx) / n_clients / send_s},
      {"lost_after_bridge", lost_after},
      {"lost_after_bridge_pct", taken_in > 0 ? 100.0 * static_cast<double>(lost_after) / (static_cast<double>(taken_in) * n_clients) : 0.0},
      {"lost_after_counted_by_bridge", bridge_counted},
      {"lost_in_client_sockets", client_kernel},
      {"lost_after_unexplained", lost_after - std::min(lost_after, bridge_counted + client_kernel)},
      {"latency_us", {{"p50", percentile(latencies_ns, 0.5)}, {"p99", percentile(latencies_ns, 0.99)}, {"max", percentile(latencies_ns, 1.0)}}},
      {"bridge_cpu_pct", 100.0 * cpu / wall_s},
      {"drain_s", drain_s},
      {"bridge_clients_link", clients_link},
  };
  return j;
}

std::vector<double> list_of(const char* text) {
  std::vector<double> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(std::atof(item.c_str()));
  return out;
}

}  // namespace

std::string us_text(double us) {
  char text[32];
  if (us >= 1e6) std::snprintf(text, sizeof text, "%.2f s", us / 1e6);
  else if (us >= 1e3) std::snprintf(text, sizeof text, "%.1f ms", us / 1e3);
  else std::snprintf(text, sizeof text, "%.0f us", us);
  return text;
}

void print_row(const nlohmann::json& j, double rate) {
  const bool peer = j["router"] != "hitl";
  const auto u = [](const nlohmann::json& v) { return static_cast<unsigned long long>(v.is_number() ? v.get<uint64_t>() : 0); };
  std::string lossless = j["lossless_lost_after"].is_null() ? "" : " (lossless " + std::to_string(u(j["lossless_lost_after"])) + ")";
  std::string reported = peer ? "not reported" : std::to_string(u(j["drops_reported"]));
  std::fprintf(stderr, "| %s | %s | %d | %llu | %llu | %.0f/s | %llu%s | %llu | %s | %s / %s | %.0f %% |\n",
               peer ? "mavlink-router" : "hitl", rate > 0 ? (std::to_string(static_cast<int>(rate)) + "/s").c_str() : "flat out",
               j["clients"].get<int>(), u(j["board_sent"]), u(j["bridge_taken_in"]), j["per_client_rate_hz"].get<double>(),
               u(j["lost_after_bridge"]) - std::min(u(j["lost_after_bridge"]), u(j["lost_in_client_sockets"])), lossless.c_str(),
               u(j["kernel_drops_board_side"]), reported.c_str(), us_text(j["latency_us"]["p50"].get<double>()).c_str(),
               us_text(j["latency_us"]["p99"].get<double>()).c_str(), j["bridge_cpu_pct"].get<double>());
}

int main(int argc, char** argv) {
  std::string hitl = hitl::test::hitl_binary(), peer, bridge_args;
  double seconds = 3;
  bool lossless = false;
  std::vector<double> clients = {1, 10, 100}, rates = {0, 1000};
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--lossless") lossless = true;
    else if (a == "--hitl" && has_value) hitl = argv[++i];
    else if (a == "--peer" && has_value) peer = argv[++i];
    else if (a == "--bridge-args" && has_value) bridge_args = argv[++i];
    else if (a == "--seconds" && has_value) seconds = std::atof(argv[++i]);
    else if (a == "--clients" && has_value) clients = list_of(argv[++i]);
    else if (a == "--rates" && has_value) rates = list_of(argv[++i]);
    else {
      std::fprintf(stderr, "usage: %s [--hitl PATH] [--seconds S] [--clients 1,10,100] [--rates 0,1000] [--peer CMD] [--lossless] [--bridge-args \"--queue-ms 500\"]\n", argv[0]);
      return 2;
    }
  }
  std::signal(SIGPIPE, SIG_IGN);
  std::fprintf(stderr,
               "| router | board rate | clients | sent | taken in | per-client rate | lost after intake | kernel drops (board side) | drops reported | p50 / p99 latency | CPU |\n"
               "|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const double rate : rates) {
    for (const double n : clients) {
      for (int router = 0; router < (peer.empty() ? 1 : 2); ++router) {
        const auto j = run_once(hitl, Run{static_cast<int>(n), rate, seconds, router == 0 ? std::string{} : peer, lossless && router == 0, bridge_args});
        std::printf("%s\n", j.dump().c_str());
        std::fflush(stdout);
        print_row(j, rate);
      }
    }
  }
  return 0;
}
