// libFuzzer target for the flight files: trajectory JSON (`-t`) and QGroundControl .params files
// (`params load`). The first byte picks the parser, the rest is the file. A trajectory that
// parses must be flyable: finite references over its whole time span.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "engine/vehicle/params_file.h"
#include "engine/vehicle/trajectory.h"
#include "tests/fuzz/fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* bytes, std::size_t size) {
  if (size == 0) return 0;
  const std::string_view text(reinterpret_cast<const char*>(bytes + 1), size - 1);
  if (bytes[0] % 2 == 0) {
    auto t = hitl::vehicle::Trajectory::parse(text, "t.json");
    if (!t) {
      FUZZ_CHECK(!t.error().message.empty());
      return 0;
    }
    FUZZ_CHECK(std::isfinite(t->duration_s()) && t->duration_s() >= 0 && t->duration_s() <= 86400);
    for (double f : {-1.0, 0.0, 0.3, 0.5, 0.99, 1.0, 2.0}) {
      const auto r = t->at(f * t->duration_s());
      for (double v : r.p_ENU_m) FUZZ_CHECK(std::isfinite(v));
      FUZZ_CHECK(std::isfinite(r.yaw_ENU_rad));
    }
  } else {
    auto p = hitl::vehicle::parse_params(text, "f.params");
    if (!p) FUZZ_CHECK(!p.error().message.empty());
    else
      for (const auto& param : *p) FUZZ_CHECK(!param.name.empty() && param.name.size() <= 16);
  }
  return 0;
}
