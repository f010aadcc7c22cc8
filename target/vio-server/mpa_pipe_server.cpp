#include "target/vio-server/mpa_pipe_server.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/inotify.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <system_error>

namespace hitl::vio {
namespace {

namespace fs = std::filesystem;

constexpr mode_t kDirMode = S_IRWXU | S_IRWXG | S_IROTH | S_IXOTH;  // 0775, as misc.c's _mkdir_recursive
constexpr mode_t kFifoMode = 0666;                                   // as server.c's mkfifo calls

std::string errno_text() { return std::strerror(errno); }

/// mkdir -p with libmodal_pipe's mode.
Status make_dirs(const std::string& dir) {
  std::string partial;
  std::istringstream parts(dir);
  std::string part;
  if (!dir.empty() && dir[0] == '/') partial = "/";
  while (std::getline(parts, part, '/')) {
    if (part.empty()) continue;
    partial += part + "/";
    if (::mkdir(partial.c_str(), kDirMode) != 0 && errno != EEXIST) {
      return Error{"cannot create the MPA directory " + partial + ": " + errno_text()};
    }
  }
  return Ok{};
}

/// The pid in an existing pipe's info file, or 0.
int info_server_pid(const std::string& info_path) {
  std::ifstream in(info_path);
  if (!in) return 0;
  const auto doc = nlohmann::json::parse(in, nullptr, false);
  if (!doc.is_object() || !doc.contains("server_pid") || !doc["server_pid"].is_number_integer()) return 0;
  return doc["server_pid"].get<int>();
}

bool process_alive(int pid) { return pid > 0 && (::kill(pid, 0) == 0 || errno == EPERM); }

}  // namespace

MpaPipeServer::MpaPipeServer(std::string location, PipeInfo info) : location_(std::move(location)), info_(std::move(info)) {}

Expected<std::unique_ptr<MpaPipeServer>> MpaPipeServer::create(const std::string& base_dir, const PipeInfo& info) {
  if (info.name.empty() || info.name.size() >= kMpaMaxNameLen || info.name.find('/') != std::string::npos) {
    return Error{"invalid MPA pipe name \"" + info.name + "\""};
  }
  if (base_dir.empty() || base_dir[0] != '/') return Error{"the MPA base directory must be an absolute path, not \"" + base_dir + "\""};
  std::string base = base_dir;
  if (base.back() != '/') base += '/';
  std::unique_ptr<MpaPipeServer> server(new MpaPipeServer(base + info.name + "/", info));
  auto started = server->start();
  if (!started.ok()) return started.error();
  return server;
}

Status MpaPipeServer::start() {
  std::error_code ec;
  if (fs::exists(location_, ec)) {
    // Left over by a server that did not clean up, or in use by a live one.
    const int pid = info_server_pid(location_ + "info");
    if (pid != ::getpid() && process_alive(pid)) {
      return Error{"MPA pipe " + location_ + " is already served by process " + std::to_string(pid) +
                   "; stop that server first"};
    }
    fs::remove_all(location_, ec);
    if (ec) return Error{"cannot remove the stale MPA pipe " + location_ + ": " + ec.message()};
    event("removed a stale " + location_ + (pid > 0 ? " left by process " + std::to_string(pid) + ", which has exited" : ""));
  }
  auto made = make_dirs(location_);
  if (!made.ok()) return made;

  nlohmann::json doc = nlohmann::json::object();
  doc["name"] = info_.name;
  doc["location"] = location_;
  doc["type"] = info_.type;
  doc["server_name"] = info_.server_name;
  doc["size_bytes"] = info_.size_bytes;
  doc["server_pid"] = static_cast<int>(::getpid());
  const std::string tmp = location_ + ".info.tmp";
  {
    std::ofstream out(tmp);
    out << doc.dump(1, '\t') << "\n";
    if (!out) return Error{"cannot write " + tmp + ": " + errno_text()};
  }
  if (::rename(tmp.c_str(), (location_ + "info").c_str()) != 0) return Error{"cannot write " + location_ + "info: " + errno_text()};

  const std::string request = location_ + "request";
  if (::mkfifo(request.c_str(), kFifoMode) != 0 && errno != EEXIST) return Error{"cannot create " + request + ": " + errno_text()};
  // Open read-write so the FIFO never reports end-of-file between clients (as server.c does).
  request_fd_ = ::open(request.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
  if (request_fd_ < 0) return Error{"cannot open " + request + ": " + errno_text()};

  inotify_fd_ = ::inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
  if (inotify_fd_ < 0) return Error{"inotify for " + location_ + ": " + errno_text()};
  if (::inotify_add_watch(inotify_fd_, location_.c_str(), IN_CLOSE_NOWRITE) < 0) {
    return Error{"inotify watch on " + location_ + ": " + errno_text()};
  }
  return Ok{};
}

MpaPipeServer::~MpaPipeServer() {
  for (auto& c : clients_) {
    if (c.fd >= 0) ::close(c.fd);
  }
  if (request_fd_ >= 0) ::close(request_fd_);
  if (inotify_fd_ >= 0) ::close(inotify_fd_);
  std::error_code ec;
  // Only what this server made: never a directory another live server took over meanwhile.
  const int pid = info_server_pid(location_ + "info");
  if (pid == 0 || pid == ::getpid()) fs::remove_all(location_, ec);
}

std::vector<int> MpaPipeServer::poll_fds() const { return {request_fd_, inotify_fd_}; }

bool MpaPipeServer::connecting() const {
  return std::any_of(clients_.begin(), clients_.end(), [](const Client& c) { return c.fd < 0; });
}

int MpaPipeServer::clients() const { return static_cast<int>(clients_.size()); }

std::vector<std::string> MpaPipeServer::take_events() {
  std::vector<std::string> out;
  out.swap(events_);
  return out;
}

void MpaPipeServer::event(std::string text) {
  if (events_.size() < 100) events_.push_back(std::move(text));
}

void MpaPipeServer::service() {
  read_requests();
  read_disconnects();
  for (auto& c : clients_) {
    if (c.fd < 0) try_open(c);
  }
  const auto now = std::chrono::steady_clock::now();
  for (std::size_t i = clients_.size(); i-- > 0;) {
    if (clients_[i].fd < 0 && now > clients_[i].deadline) drop(i, "did not open its FIFO within 1 s");
  }
}

std::string MpaPipeServer::check_client_name(const std::string& name) const {
  if (name.empty()) return "the name is empty";
  if (name.size() >= kMpaMaxNameLen) return "the name is longer than " + std::to_string(kMpaMaxNameLen - 1) + " characters";
  for (char ch : name) {
    if (ch < ' ' || ch > 'z') return "the name has a character outside ' '..'z' (code " + std::to_string(int(uint8_t(ch))) + ")";
    if (ch == '/') return "the name has a '/'";
  }
  if (name == "." || name == ".." || name == "request" || name == "info" || name == "control") return "the name is reserved";
  for (const auto& c : clients_) {
    if (c.name == name) return "a client of that name is connected";
  }
  if (clients_.size() >= static_cast<std::size_t>(kMpaMaxClients)) return "the pipe has " + std::to_string(kMpaMaxClients) + " clients already";
  return {};
}

void MpaPipeServer::read_requests() {
  char buf[4096];
  for (;;) {
    const ssize_t n = ::read(request_fd_, buf, sizeof buf);
    if (n <= 0) return;  // EAGAIN: nothing more
    // Each request is a name and its NUL; several may arrive in one read.
    std::size_t start = 0;
    for (std::size_t i = 0; i <= static_cast<std::size_t>(n); ++i) {
      if (i == static_cast<std::size_t>(n) || buf[i] == '\0') {
        if (i > start) add_client(std::string(buf + start, i - start));
        start = i + 1;
      }
    }
  }
}

void MpaPipeServer::add_client(const std::string& name) {
  const std::string problem = check_client_name(name);
  if (!problem.empty()) {
    ++counters_.requests_rejected;
    std::string shown;
    for (char ch : name.substr(0, 40)) shown += (ch >= ' ' && ch <= '~') ? ch : '?';
    event("refused a request on " + location_ + "request for \"" + shown + "\": " + problem);
    return;
  }
  Client c;
  c.name = name;
  c.path = location_ + name;
  c.deadline = std::chrono::steady_clock::now() + kClientOpenTimeout;
  if (::mkfifo(c.path.c_str(), kFifoMode) != 0 && errno != EEXIST) {
    ++counters_.requests_rejected;
    event("cannot create " + c.path + ": " + errno_text());
    return;
  }
  clients_.push_back(std::move(c));
  try_open(clients_.back());
}

void MpaPipeServer::try_open(Client& c) {
  // Succeeds once the client is in (or has finished) its open for reading; ENXIO until then.
  const int fd = ::open(c.path.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return;
  c.fd = fd;
  const int wanted = info_.size_bytes;
  int size = ::fcntl(fd, F_SETPIPE_SZ, wanted);
  if (size < wanted) {
    size = ::fcntl(fd, F_GETPIPE_SZ);
    event("pipe size of " + c.path + " is " + std::to_string(size) + " bytes, not the " + std::to_string(wanted) +
          " asked for (/proc/sys/fs/pipe-max-size)");
  }
  c.pipe_size_bytes = size;
  ++counters_.clients_accepted;
  event("client " + c.name + " connected to " + location_);
}

void MpaPipeServer::read_disconnects() {
  alignas(inotify_event) char buf[4096];
  for (;;) {
    const ssize_t n = ::read(inotify_fd_, buf, sizeof buf);
    if (n <= 0) return;
    for (ssize_t off = 0; off + static_cast<ssize_t>(sizeof(inotify_event)) <= n;) {
      const auto* e = reinterpret_cast<const inotify_event*>(buf + off);
      off += static_cast<ssize_t>(sizeof(inotify_event) + e->len);
      if (e->len == 0 || (e->mask & IN_ISDIR)) continue;
      const std::string name(e->name);
      for (std::size_t i = 0; i < clients_.size(); ++i) {
        // A client still connecting has not opened the FIFO; its close is not a disconnect.
        if (clients_[i].name == name && clients_[i].fd >= 0) {
          drop(i, "closed its end");
          break;
        }
      }
    }
  }
}

void MpaPipeServer::drop(std::size_t index, const std::string& why) {
  Client& c = clients_[index];
  if (c.fd >= 0) ::close(c.fd);
  ::unlink(c.path.c_str());
  event("client " + c.name + " of " + location_ + " " + why + "; removed " + c.path);
  clients_.erase(clients_.begin() + static_cast<std::ptrdiff_t>(index));
}

bool MpaPipeServer::write_to(Client& c, const uint8_t* data, std::size_t len) {
  const ssize_t n = ::write(c.fd, data, len);
  if (n == static_cast<ssize_t>(len)) return true;
  if (n > 0) {
    c.backlog.assign(data + n, data + len);
    return true;
  }
  return false;
}

void MpaPipeServer::write(std::span<const uint8_t> record) {
  for (std::size_t i = clients_.size(); i-- > 0;) {
    Client& c = clients_[i];
    if (c.fd < 0) continue;
    // Finish a record a previous write cut short before starting another, so records stay whole.
    if (!c.backlog.empty()) {
      const ssize_t n = ::write(c.fd, c.backlog.data(), c.backlog.size());
      if (n > 0) c.backlog.erase(c.backlog.begin(), c.backlog.begin() + n);
      if (n < 0 && errno == EPIPE) {
        drop(i, "is gone (EPIPE)");
        continue;
      }
      if (!c.backlog.empty()) {
        ++counters_.records_dropped;
        continue;
      }
    }
    int queued = 0;
    if (::ioctl(c.fd, FIONREAD, &queued) == 0 && c.pipe_size_bytes - queued < static_cast<int>(record.size())) {
      ++counters_.records_dropped;  // the client is behind: skip this record rather than block
      continue;
    }
    if (write_to(c, record.data(), record.size())) {
      ++counters_.records_written;
    } else if (errno == EPIPE) {
      drop(i, "is gone (EPIPE)");
    } else {
      ++counters_.records_dropped;
    }
  }
}

}  // namespace hitl::vio
