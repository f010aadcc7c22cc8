// make_pipe_server() for builds that found libmodal_pipe (the VOXL SDK): ModalAI's own server,
// through its public API (modal_pipe_server.h): pipe_server_create, pipe_server_write,
// pipe_server_get_num_clients, pipe_server_close. The library runs its own request and
// disconnect threads, so there is nothing to poll; it does not report per-record drops.
#include <modal_pipe_server.h>

#include <cstring>

#include "target/vio-server/pipe_server.h"

namespace hitl::vio {
namespace {

int next_channel = 0;  // libmodal_pipe numbers a process's server channels from 0

void copy_field(char* to, std::size_t size, const std::string& from) {
  std::strncpy(to, from.c_str(), size - 1);
  to[size - 1] = '\0';
}

class LibModalPipeServer final : public PipeServer {
 public:
  LibModalPipeServer(int channel, std::string location) : channel_(channel), location_(std::move(location)) {}
  ~LibModalPipeServer() override { pipe_server_close(channel_); }

  std::vector<int> poll_fds() const override { return {}; }
  void service() override {}
  bool connecting() const override { return false; }
  void write(std::span<const uint8_t> record) override {
    // char* fits both the old (char* data) and the current (const void* data) signature.
    pipe_server_write(channel_, reinterpret_cast<char*>(const_cast<uint8_t*>(record.data())), static_cast<int>(record.size()));
    counters_.records_written += static_cast<uint64_t>(clients());
  }
  int clients() const override { return pipe_server_get_num_clients(channel_); }
  PipeCounters counters() const override { return counters_; }
  std::vector<std::string> take_events() override { return {}; }
  const std::string& location() const override { return location_; }

 private:
  int channel_;
  std::string location_;
  PipeCounters counters_;
};

}  // namespace

Expected<std::unique_ptr<PipeServer>> make_pipe_server(const std::string& base_dir, const PipeInfo& info) {
  if (base_dir.empty() || base_dir[0] != '/') return Error{"the MPA base directory must be an absolute path, not \"" + base_dir + "\""};
  std::string location = base_dir;
  if (location.back() != '/') location += '/';
  location += info.name + "/";
  if (location.size() >= sizeof(pipe_info_t{}.location)) {
    return Error{"MPA pipe location " + location + " is longer than libmodal_pipe allows"};
  }
  pipe_info_t pipe_info = PIPE_INFO_INITIALIZER;
  copy_field(pipe_info.name, sizeof pipe_info.name, info.name);
  copy_field(pipe_info.location, sizeof pipe_info.location, location);
  copy_field(pipe_info.type, sizeof pipe_info.type, info.type);
  copy_field(pipe_info.server_name, sizeof pipe_info.server_name, info.server_name);
  pipe_info.size_bytes = info.size_bytes;
  const int channel = next_channel++;
  if (pipe_server_create(channel, pipe_info, 0) != 0) {
    return Error{"libmodal_pipe could not create the MPA pipe " + location + " (see its message above)"};
  }
  return std::unique_ptr<PipeServer>(new LibModalPipeServer(channel, location));
}

const char* pipe_server_implementation() { return "libmodal_pipe"; }

}  // namespace hitl::vio
