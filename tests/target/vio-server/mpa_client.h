// A test client of an MPA pipe that connects the way libmodal_pipe's pipe_client does
// (client.c, _connect_to_server): it writes "<name><8 random digits>" and its NUL to the pipe's
// request FIFO, then opens that data FIFO for reading with a blocking open, retrying every 1 ms
// while it does not exist yet (client.c gives up after 500 tries), and reads whole records.
// Unlike client.c it never hangs a test: a blocking open that outlives its timeout is released.
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

namespace hitl::test {

class MpaClient {
 public:
  MpaClient() = default;
  MpaClient(MpaClient&& other) noexcept;
  MpaClient& operator=(MpaClient&& other) noexcept;
  MpaClient(const MpaClient&) = delete;
  MpaClient& operator=(const MpaClient&) = delete;
  ~MpaClient();

  /// Connects to the pipe whose directory is `pipe_dir` ("/run/mpa/hitl_vio/"). Empty `error` on
  /// success; otherwise it says what failed.
  static MpaClient connect(const std::string& pipe_dir, const std::string& client_name, std::string& error,
                           std::chrono::milliseconds timeout = std::chrono::seconds(3));

  bool connected() const { return fd_ >= 0; }
  int fd() const { return fd_; }
  const std::string& fifo_path() const { return fifo_path_; }
  /// Reads exactly `len` bytes; false on timeout or end of file (the server closed its end).
  bool read_exact(void* out, std::size_t len, std::chrono::milliseconds timeout);
  /// Bytes waiting in the FIFO (FIONREAD).
  int queued() const;
  void close();

 private:
  int fd_ = -1;
  std::string fifo_path_;
};

/// "<name truncated to 23 characters><8 digits>", as client.c forms it.
std::string mpa_client_fifo_name(const std::string& client_name);

}  // namespace hitl::test
