// libFuzzer target for a board's answers to the parameter and shell protocols, as `hitl params`
// and `hitl shell` collect them: the input is what the board sends (datagrams parsed as the link
// does, with the input repeated so a long answer builds up), every PARAM_VALUE goes to a
// ParamCollector and every SERIAL_CONTROL to a ShellOutput. Both must stay bounded.
#include <cstddef>
#include <cstdint>

#include "base/mavlink/frame_parser.h"
#include "base/mavlink/message_set.h"
#include "engine/vehicle/board_replies.h"
#include "tests/fuzz/fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* bytes, std::size_t size) {
  using namespace hitl;
  static const mavlink::MessageSet messages = mavlink::MessageSet::compiled();
  mavlink::FrameParser parser(messages);
  vehicle::ParamCollector params;
  vehicle::ShellOutput shell;
  const int repeats = size ? 1 + bytes[0] % 8 : 1;
  for (int r = 0; r < repeats; ++r) {
    parser.parse_datagram({bytes, size}, [&](const mavlink::Frame& f) {
      if (f.is<mavlink::msg::ParamValue>()) {
        const bool done = params.take(f.as<mavlink::msg::ParamValue>());
        FUZZ_CHECK(!done || params.received() == *params.total());
        FUZZ_CHECK(!vehicle::param_name(f.as<mavlink::msg::ParamValue>().param_id).empty() ||
                   f.as<mavlink::msg::ParamValue>().param_id[0] == '\0');
      } else if (f.is<mavlink::msg::SerialControl>()) {
        (void)shell.append(f.as<mavlink::msg::SerialControl>());
      }
    });
  }
  FUZZ_CHECK(params.received() <= 65535);
  for (const auto& p : params.params()) FUZZ_CHECK(p.name.size() <= 16);
  FUZZ_CHECK(shell.text().size() <= vehicle::kMaxShellOutputBytes);
  FUZZ_CHECK(shell.body().size() <= shell.text().size());
  return 0;
}
