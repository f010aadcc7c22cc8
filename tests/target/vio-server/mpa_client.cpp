#include "tests/target/vio-server/mpa_client.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <future>
#include <random>
#include <thread>

namespace hitl::test {

std::string mpa_client_fifo_name(const std::string& client_name) {
  static std::mt19937 rng{std::random_device{}()};
  char digits[9];
  std::snprintf(digits, sizeof digits, "%08d", std::uniform_int_distribution<int>(0, 99999999)(rng));
  return client_name.substr(0, 23) + digits;  // MODAL_PIPE_MAX_NAME_LEN 32 - 8 digits - NUL
}

MpaClient::MpaClient(MpaClient&& other) noexcept : fd_(other.fd_), fifo_path_(std::move(other.fifo_path_)) { other.fd_ = -1; }

MpaClient& MpaClient::operator=(MpaClient&& other) noexcept {
  if (this != &other) {
    close();
    fd_ = other.fd_;
    fifo_path_ = std::move(other.fifo_path_);
    other.fd_ = -1;
  }
  return *this;
}

MpaClient::~MpaClient() { close(); }

void MpaClient::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

MpaClient MpaClient::connect(const std::string& pipe_dir, const std::string& client_name, std::string& error,
                             std::chrono::milliseconds timeout) {
  MpaClient client;
  const std::string request = pipe_dir + "request";
  if (::access(request.c_str(), F_OK) != 0) {
    error = "no request FIFO at " + request + " (server not available)";
    return client;
  }
  const std::string name = mpa_client_fifo_name(client_name);
  client.fifo_path_ = pipe_dir + name;
  const int req = ::open(request.c_str(), O_WRONLY | O_NONBLOCK);
  if (req < 0) {
    error = "cannot open " + request + ": " + std::strerror(errno);
    return client;
  }
  const ssize_t n = ::write(req, name.c_str(), name.size() + 1);
  ::close(req);
  if (n != static_cast<ssize_t>(name.size() + 1)) {
    error = "cannot write the request to " + request;
    return client;
  }
  // client.c: open(data_path, O_RDONLY) until it exists; the open blocks until the server opens
  // its end for writing.
  const std::string path = client.fifo_path_;
  auto opened = std::async(std::launch::async, [path, timeout] {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
      const int fd = ::open(path.c_str(), O_RDONLY);
      if (fd >= 0) return fd;
      if (errno != ENOENT && errno != EINTR) return -errno;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return -ETIMEDOUT;
  });
  if (opened.wait_for(timeout + std::chrono::milliseconds(500)) != std::future_status::ready) {
    // Stuck in the blocking open: the server made the FIFO but never opened it. Release it.
    const int unblock = ::open(path.c_str(), O_WRONLY | O_NONBLOCK);
    const int fd = opened.get();
    if (fd >= 0) ::close(fd);
    if (unblock >= 0) ::close(unblock);
    error = "the server made " + path + " but never opened it for writing";
    return client;
  }
  const int fd = opened.get();
  if (fd < 0) {
    error = "cannot open " + path + ": " + std::strerror(-fd);
    return client;
  }
  client.fd_ = fd;
  return client;
}

bool MpaClient::read_exact(void* out, std::size_t len, std::chrono::milliseconds timeout) {
  auto* p = static_cast<char*>(out);
  std::size_t got = 0;
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (got < len) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return false;
    pollfd pfd{fd_, POLLIN, 0};
    if (::poll(&pfd, 1, static_cast<int>(left.count())) <= 0) continue;
    const ssize_t n = ::read(fd_, p + got, len - got);
    if (n == 0) return false;  // the server closed its end
    if (n < 0) {
      if (errno == EINTR || errno == EAGAIN) continue;
      return false;
    }
    got += static_cast<std::size_t>(n);
  }
  return true;
}

int MpaClient::queued() const {
  int n = 0;
  ::ioctl(fd_, FIONREAD, &n);
  return n;
}

}  // namespace hitl::test
