// libFuzzer target for `hitl report --plot` (engine/report/field_expression.h): any bytes as a --plot
// value, parsed against the codec's messages. A refusal is an input error naming the value and a
// character of it, under 4 KiB; an accepted plot has 1 to 8 series, each of one message, within its
// node bound, whose evaluation on any payload (these bytes, zero-extended) returns (finite or not)
// without reading past the payload.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "base/mavlink/frame.h"
#include "base/mavlink/message_set.h"
#include "engine/report/field_expression.h"
#include "tests/fuzz/fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* bytes, std::size_t size) {
  static const auto messages = hitl::mavlink::MessageSet::compiled();
  const std::string_view text(reinterpret_cast<const char*>(bytes), size);
  const hitl::report::FieldPlotLimits limits;
  auto spec = hitl::report::parse_field_plot(text, messages, limits);
  if (!spec) {
    FUZZ_CHECK(spec.error().kind == hitl::ErrorKind::Input);
    FUZZ_CHECK(spec.error().message.size() < 4096);
    FUZZ_CHECK(spec.error().message.rfind("'", 0) == 0 && spec.error().message.find("' at character ") != std::string::npos);
    return 0;
  }
  FUZZ_CHECK(!spec->series.empty() && spec->series.size() <= limits.max_series);
  std::array<uint8_t, hitl::mavlink::kMaxPayloadLen> payload{};
  std::copy_n(bytes, std::min(size, payload.size()), payload.begin());
  for (const auto& e : spec->series) {
    FUZZ_CHECK(!e.message.empty() && messages.find(e.msgid) != nullptr && messages.find(e.msgid)->name == e.message);
    FUZZ_CHECK(!e.nodes.empty() && e.nodes.size() <= limits.max_nodes);
    for (const auto& n : e.nodes)
      if (n.op == hitl::report::FieldExpression::Op::Field)
        FUZZ_CHECK(n.field != nullptr && n.field->offset + n.field->wire_size() <= hitl::mavlink::kMaxPayloadLen);
    (void)e.evaluate(payload.data());
  }
  return 0;
}
