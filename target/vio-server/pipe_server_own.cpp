// make_pipe_server() for builds without libmodal_pipe: hitl's implementation of its protocol.
#include "target/vio-server/mpa_pipe_server.h"
#include "target/vio-server/pipe_server.h"

namespace hitl::vio {

Expected<std::unique_ptr<PipeServer>> make_pipe_server(const std::string& base_dir, const PipeInfo& info) {
  auto server = MpaPipeServer::create(base_dir, info);
  if (!server.ok()) return server.error();
  return std::unique_ptr<PipeServer>(std::move(server.value()));
}

const char* pipe_server_implementation() { return "hitl's MPA implementation"; }

}  // namespace hitl::vio
