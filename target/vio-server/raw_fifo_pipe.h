// hitl_vio as voxl-vision-hub's en_hitl reader opens it (state_manager.c, hitl_vio_thread): not an
// MPA pipe directory but one FIFO at <base>/hitl_vio, which vision-hub opens O_RDWR, flushes, and
// reads vio_data_t records from. ModalAI's own ODOMETRY bridge (mavlink_odometry_bridge.cpp) made
// that FIFO with mkfifo(0666) and held it open O_RDWR, and so does this: records written while no
// one reads wait in the FIFO (vision-hub flushes them when it starts); a full FIFO drops records
// whole. `voxl-hitl-vio-server --vision-hub-fifo` publishes hitl_vio this way; hitl_vio_extended
// stays an MPA pipe. The path cannot be both, so it is one or the other.
#pragma once

#include <memory>
#include <string>

#include "target/vio-server/pipe_server.h"

namespace hitl::vio {

class RawFifoPipe final : public PipeServer {
 public:
  /// Makes (or reuses) the FIFO `<base_dir><name>`; refuses a path that is something else, such as
  /// an MPA pipe directory another server is serving.
  static Expected<std::unique_ptr<RawFifoPipe>> create(const std::string& base_dir, const std::string& name, int size_bytes);
  ~RawFifoPipe() override;  ///< closes and removes the FIFO

  std::vector<int> poll_fds() const override { return {}; }
  void service() override {}
  bool connecting() const override { return false; }
  void write(std::span<const uint8_t> record) override;
  /// A FIFO does not say who reads it: -1.
  int clients() const override { return -1; }
  PipeCounters counters() const override { return counters_; }
  std::vector<std::string> take_events() override;
  const std::string& location() const override { return path_; }

 private:
  RawFifoPipe(std::string path, int fd, int size_bytes);

  std::string path_;
  int fd_;
  int size_bytes_;
  PipeCounters counters_;
  std::vector<std::string> events_;
};

}  // namespace hitl::vio
