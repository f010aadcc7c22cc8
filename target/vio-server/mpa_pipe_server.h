// hitl's own implementation of the server side of libmodal_pipe's protocol, for builds without
// the library. The facts, from libmodal_pipe's server.c, client.c and misc.c:
//
//   <base>/<name>/           the pipe's directory, mode 0775, created with its parents
//   <base>/<name>/info       JSON: name, location, type, server_name, size_bytes, server_pid
//   <base>/<name>/request    FIFO (0666) the server holds open O_RDWR. A client writes the name of
//                            the data FIFO it wants, NUL included: its own name truncated to 23
//                            characters plus 8 random digits ("voxl-vision-hub01234567").
//   <base>/<name>/<client>   that client's data FIFO (0666), made by the server on the request and
//                            opened O_WRONLY|O_NONBLOCK once the client has it open for reading
//                            (the client retries its blocking open for 0.5 s); its size is set to
//                            info.size_bytes with F_SETPIPE_SZ. Records are written whole.
//   <base>/<name>/control    optional; this server creates none (a client treats ENOENT as "no
//                            control pipe"): a ground-truth source has no estimator to reset.
//
// A client is dropped, and its FIFO removed, when it closes its end: inotify IN_CLOSE_NOWRITE on
// the directory names the FIFO (that is how libmodal_pipe notices), or a write fails with EPIPE.
// A record is written to a client only when it fits whole (FIONREAD against the pipe size);
// otherwise it is dropped for that client and counted, as libmodal_pipe does.
//
// Requests are checked harder than libmodal_pipe does, since the request FIFO is world-writable:
// names must be 1..31 characters from ' ' to 'z' (MODAL_PIPE_MAX_NAME_LEN 32 with the NUL),
// without '/', not "." / "..", not "request" / "info" / "control", not a current client; at most
// 16 clients (PIPE_SERVER_MAX_CLIENTS_PER_CH).
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "target/vio-server/pipe_server.h"

namespace hitl::vio {

inline constexpr std::size_t kMpaMaxNameLen = 32;  ///< MODAL_PIPE_MAX_NAME_LEN, NUL included
inline constexpr int kMpaMaxClients = 16;          ///< PIPE_SERVER_MAX_CLIENTS_PER_CH
/// How long a requested client has to open its data FIFO before the request is abandoned.
inline constexpr std::chrono::milliseconds kClientOpenTimeout{1000};

class MpaPipeServer final : public PipeServer {
 public:
  static Expected<std::unique_ptr<MpaPipeServer>> create(const std::string& base_dir, const PipeInfo& info);
  ~MpaPipeServer() override;

  std::vector<int> poll_fds() const override;
  void service() override;
  bool connecting() const override;
  void write(std::span<const uint8_t> record) override;
  int clients() const override;
  PipeCounters counters() const override { return counters_; }
  std::vector<std::string> take_events() override;
  const std::string& location() const override { return location_; }

  /// Why a requested client name is refused, or empty when it is acceptable.
  std::string check_client_name(const std::string& name) const;

 private:
  struct Client {
    std::string name;
    std::string path;
    int fd = -1;                                        ///< -1 while connecting
    std::chrono::steady_clock::time_point deadline;     ///< connecting: give up after this
    int pipe_size_bytes = 0;
    std::vector<uint8_t> backlog;                       ///< the rest of a record a write cut short
  };

  MpaPipeServer(std::string location, PipeInfo info);
  Status start();
  void read_requests();
  void read_disconnects();
  void add_client(const std::string& name);
  void try_open(Client& client);
  void drop(std::size_t index, const std::string& why);
  bool write_to(Client& client, const uint8_t* data, std::size_t len);
  void event(std::string text);

  std::string location_;  ///< "<base>/<name>/"
  PipeInfo info_;
  int request_fd_ = -1;
  int inotify_fd_ = -1;
  std::vector<Client> clients_;
  PipeCounters counters_;
  std::vector<std::string> events_;
};

}  // namespace hitl::vio
