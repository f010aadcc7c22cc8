// libFuzzer target for the adb tunnel's framing, as either end reads the other: the hello, then
// frames split at input-derived read boundaries, and control payloads. The decoder must hold at
// most one partial frame and, once failed, stay failed.
#include <cstddef>
#include <cstdint>

#include "base/contract/datagram_framing.h"
#include "tests/fuzz/fuzz_check.h"

namespace {

struct Sink : hitl::adb::FrameDecoder::Sink {
  void on_frame(hitl::adb::Channel channel, const uint8_t* payload, std::size_t size) override {
    FUZZ_CHECK(size <= hitl::adb::kMaxDatagram_bytes);
    if (channel == hitl::adb::Channel::Control) (void)hitl::adb::parse_control(payload, size);
    ++frames;
  }
  uint64_t frames = 0;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* bytes, std::size_t size) {
  using namespace hitl::adb;
  const auto hello = parse_hello(bytes, size);
  FUZZ_CHECK(hello.hello.has_value() == hello.error.empty());
  (void)starts_like_hello(bytes, size < 12 ? size : 11);
  FUZZ_CHECK(!not_a_tunnel_error(bytes, size).empty());

  const std::size_t chunk = 1 + (size ? bytes[0] : 0) % 97;
  FrameDecoder decoder;
  Sink sink;
  bool ok = true;
  for (std::size_t pos = 0; pos < size; pos += chunk) {
    const std::size_t n = chunk < size - pos ? chunk : size - pos;
    const bool fed = decoder.feed(bytes + pos, n, sink);
    if (!ok) FUZZ_CHECK(!fed);  // failed stays failed
    ok = ok && fed;
    FUZZ_CHECK(decoder.buffered() <= 3 + 2 + kMaxDatagram_bytes + 16);
  }
  FUZZ_CHECK(decoder.frames() == sink.frames);
  FUZZ_CHECK(ok == !decoder.failed());
  return 0;
}
