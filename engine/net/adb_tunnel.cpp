#include "engine/net/adb_tunnel.h"

#include <sys/stat.h>

#include <chrono>
#include <thread>

#include "engine/net/executable_arch.h"

namespace hitl::net {
namespace {

std::string one_line(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r' || text.back() == ' ')) text.pop_back();
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  return text;
}

bool is_file(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

}  // namespace

Expected<std::unique_ptr<AdbTunnel>> AdbTunnel::open(const AdbTunnelConfig& config) {
  auto adb = Adb::connect(config.serial);
  if (!adb) return adb.error();
  std::unique_ptr<AdbTunnel> t(new AdbTunnel(config, std::move(adb.value())));
  AdbTunnel* self = t.get();
  auto tunnel = DatagramTunnel::open(config.tunnel, [self] { return self->establish(); });
  if (!tunnel) return tunnel.error();  // the destructor removes a forward made on the way
  t->tunnel_ = std::move(tunnel.value());
  return t;
}

AdbTunnel::AdbTunnel(const AdbTunnelConfig& config, Adb adb) : config_(config), adb_(std::move(adb)) {}

AdbTunnel::~AdbTunnel() {
  tunnel_.reset();  // the pump is stopped before the forward goes
  const uint16_t port = forward_port();
  if (port == 0) return;
  if (auto removed = adb_.remove_forward(port); !removed) emit("adb tunnel: " + removed.error().message);
  else emit("adb tunnel: removed the forward tcp:" + std::to_string(port));
}

uint16_t AdbTunnel::forward_port() const {
  std::lock_guard<std::mutex> lock(forward_mutex_);
  return forward_port_;
}

std::string AdbTunnel::describe() const {
  std::string out = "board " + adb_.serial() + " through adb forward tcp:" + std::to_string(forward_port()) + " -> tcp:" +
                    std::to_string(config_.relay_port) + " (hitl-adb-relay)";
  for (adb::Channel c : adb::kDataChannels)
    out += std::string(c == adb::Channel::Hil ? "; " : ", ") + adb::to_string(c) + " " + local_endpoint(c).to_string();
  return out;
}

void AdbTunnel::emit(const std::string& line) const {
  if (config_.tunnel.on_event) config_.tunnel.on_event(line);
}

Status AdbTunnel::make_forward() {
  const uint16_t old = forward_port();
  if (old != 0) (void)adb_.remove_forward(old);  // a replugged board has lost it anyway
  auto port = adb_.forward(config_.relay_port);
  std::lock_guard<std::mutex> lock(forward_mutex_);
  forward_port_ = port ? *port : 0;
  if (!port) return port.error();
  return Ok{};
}

Expected<std::string> AdbTunnel::relay_to_push() {
  auto uname = adb_.shell("uname -m");
  if (!uname) return uname.error();
  const std::string machine = normalize_machine(one_line(uname->out));
  if (machine.empty()) return Error::failed("cannot tell the board's architecture: `adb shell uname -m` printed nothing");
  std::string tried;
  for (const auto& path : config_.relay_binaries) {
    if (!is_file(path)) {
      tried += (tried.empty() ? "" : ", ") + path + " (missing)";
      continue;
    }
    const auto arch = executable_architecture(path);
    if (arch && *arch == machine) return path;
    tried += (tried.empty() ? "" : ", ") + path + " (" + (arch ? *arch : std::string("not an executable")) + ")";
  }
  return Error::failed("hitl-adb-relay is not on the board and there is no copy built for the board's " + machine +
                       " to push (tried: " + (tried.empty() ? std::string("none") : tried) +
                       "): install the voxl-hitl-px4-scripts package on the board, or build the relay for " + machine +
                       " (docs/adb.md) and pass --adb-relay FILE");
}

Status AdbTunnel::start_relay() {
  const std::string args = " --daemon --port " + std::to_string(config_.relay_port);
  // The board package's copy on the board's PATH, then one pushed earlier, then push one.
  for (int attempt = 0; attempt < 3; ++attempt) {
    const std::string program = attempt == 0 ? adb::kRelayProgram : adb::kPushedRelayPath;
    if (attempt == 2) {
      auto local = relay_to_push();
      if (!local) return local.error();
      emit("adb tunnel: hitl-adb-relay is not on the board; pushing " + *local + " to " + adb::kPushedRelayPath);
      if (auto pushed = adb_.push(*local, adb::kPushedRelayPath); !pushed) return pushed.error();
      if (auto chmod = adb_.shell(std::string("chmod 755 ") + adb::kPushedRelayPath); !chmod) return chmod.error();
    }
    auto out = adb_.shell(program + args);
    if (!out) return out.error();
    const std::string text = one_line(out->out + out->err);
    if (out->exit_code == 0 && text.find("listening on TCP") != std::string::npos) {
      emit("adb tunnel: started " + program + " on the board: " + text);
      return Ok{};
    }
    const bool missing = out->exit_code == 127 || text.find("not found") != std::string::npos ||
                         text.find("No such file") != std::string::npos;
    if (!missing || attempt == 2)
      return Error::failed("starting hitl-adb-relay on the board failed: `adb shell " + program + args + "` said: " +
                           (text.empty() ? "nothing (exit " + std::to_string(out->exit_code) + ")" : text));
  }
  return Error::failed("starting hitl-adb-relay on the board failed");
}

Expected<std::unique_ptr<adb::FramedStream>> AdbTunnel::establish() {
  auto connect = [this] {
    auto address = SocketAddress::resolve("127.0.0.1", forward_port());
    if (!address) return RelayConnection{nullptr, address.error().message, false};
    return connect_to_relay(*address, config_.handshake_timeout_ms);
  };
  // 1. Through the forward we have (the first time: a new one).
  const bool fresh_forward = forward_port() == 0;
  if (fresh_forward) {
    if (auto made = make_forward(); !made) return made.error();
  }
  auto r = connect();
  if (r.stream) return std::move(r.stream);
  if (!r.relay_absent) return Error::failed(r.error);
  // 2. A board unplugged and back has lost its forwards: make it again.
  if (!fresh_forward) {
    if (auto made = make_forward(); !made) return made.error();
    r = connect();
    if (r.stream) return std::move(r.stream);
    if (!r.relay_absent) return Error::failed(r.error);
  }
  // 3. Nothing listens on the board: start the relay (pushing it when the board has none).
  if (auto started = start_relay(); !started) return started.error();
  for (int attempt = 0; attempt < 5; ++attempt) {
    r = connect();
    if (r.stream) return std::move(r.stream);
    if (!r.relay_absent) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  return Error::failed("hitl-adb-relay started on the board but does not answer: " + r.error +
                       " (its log: adb shell cat " + adb::kRelayDaemonLogPath + ")");
}

}  // namespace hitl::net
