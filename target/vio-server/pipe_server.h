// The server end of one MPA pipe (ModalAI Pipe Architecture), whichever implementation the build
// chose: libmodal_pipe's pipe_server when the build finds the library (the board's SDK), otherwise
// hitl's own implementation of the same protocol (mpa_pipe_server.h).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "base/common/expected.h"

namespace hitl::vio {

/// MODAL_PIPE_DEFAULT_BASE_DIR.
inline constexpr const char* kDefaultMpaBaseDir = "/run/mpa/";

/// What the pipe's `info` file says about it (libmodal_pipe's pipe_info_t, less the location and
/// pid, which the server fills in).
struct PipeInfo {
  std::string name;         ///< "hitl_vio": the directory under the base
  std::string type;         ///< "vio_data_t": what a record is
  std::string server_name;  ///< "voxl-hitl-vio-server"
  int size_bytes = 0;       ///< size of each client's data FIFO
};

struct PipeCounters {
  uint64_t records_written = 0;   ///< records written whole to a client (one per client)
  uint64_t records_dropped = 0;   ///< records a client's full pipe could not take
  uint64_t clients_accepted = 0;  ///< requests that became a client
  uint64_t requests_rejected = 0; ///< requests refused (bad name, duplicate, too many clients)
};

class PipeServer {
 public:
  virtual ~PipeServer() = default;  ///< closes the pipe and removes its directory
  /// File descriptors the caller polls for reading; service() when one is readable.
  virtual std::vector<int> poll_fds() const = 0;
  /// Handles client requests and disconnects without blocking.
  virtual void service() = 0;
  /// True while a requested client has not opened its FIFO yet: service() again within ~1 ms.
  virtual bool connecting() const = 0;
  /// Writes one record to every connected client.
  virtual void write(std::span<const uint8_t> record) = 0;
  virtual int clients() const = 0;
  virtual PipeCounters counters() const = 0;
  /// Things worth a log line since the last call ("client foo00012345 connected").
  virtual std::vector<std::string> take_events() = 0;
  /// The pipe's directory, "/run/mpa/hitl_vio/".
  virtual const std::string& location() const = 0;
};

/// Creates pipe `info.name` under `base_dir` (created when missing). Fails when the directory cannot
/// be made, or another live process already serves a pipe of that name.
Expected<std::unique_ptr<PipeServer>> make_pipe_server(const std::string& base_dir, const PipeInfo& info);

/// Which implementation make_pipe_server() uses: "libmodal_pipe" or "hitl's MPA implementation".
const char* pipe_server_implementation();

}  // namespace hitl::vio
