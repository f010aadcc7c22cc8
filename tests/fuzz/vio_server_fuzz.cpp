// libFuzzer target for voxl-hitl-vio-server's outside input: the datagrams on its ODOMETRY port
// (parsed as the receiver does, each ODOMETRY turned into a VIO record) and its configuration
// file. The first byte picks which.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "base/mavlink/frame_parser.h"
#include "base/mavlink/message_set.h"
#include "target/vio-server/odometry_to_vio.h"
#include "target/vio-server/vio_server_config.h"
#include "tests/fuzz/fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* bytes, std::size_t size) {
  if (size == 0) return 0;
  if (bytes[0] % 2 == 0) {
    static const hitl::mavlink::MessageSet messages = hitl::mavlink::MessageSet::compiled();
    hitl::mavlink::FrameParser parser(messages);
    parser.parse_datagram({bytes + 1, size - 1}, [](const hitl::mavlink::Frame& f) {
      if (f.desc == nullptr || !f.is<hitl::mavlink::msg::Odometry>()) return;
      (void)hitl::vio::vio_from_odometry(f.as<hitl::mavlink::msg::Odometry>(), 1'000'000'000);
    });
  } else {
    const std::string_view text(reinterpret_cast<const char*>(bytes + 1), size - 1);
    auto c = hitl::vio::parse_config(text, "voxl-hitl-vio-server.conf");
    if (!c) FUZZ_CHECK(!c.error().message.empty());
  }
  return 0;
}
