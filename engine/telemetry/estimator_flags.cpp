#include "engine/telemetry/estimator_flags.h"

#include "base/mavlink/enums.h"

namespace hitl::telemetry {

std::vector<EstimatorFlag> estimator_flags(uint16_t flags) {
  namespace e = mavlink::estimator_status;
  struct Known {
    uint16_t bit;
    const char* word;
    bool fault;
  };
  static constexpr Known kKnown[] = {
      {e::kAttitude, "attitude", false},         {e::kVelocityHoriz, "vel horiz", false},
      {e::kVelocityVert, "vel vert", false},     {e::kPosHorizRel, "pos horiz rel", false},
      {e::kPosHorizAbs, "pos horiz abs", false}, {e::kPosVertAbs, "pos vert abs", false},
      {e::kPosVertAgl, "pos vert agl", false},   {e::kConstPosMode, "const pos mode", true},
      {e::kPredPosHorizRel, "pred pos rel", false}, {e::kPredPosHorizAbs, "pred pos abs", false},
      {e::kGpsGlitch, "GPS glitch", true},       {e::kAccelError, "accel error", true}};
  std::vector<EstimatorFlag> out;
  out.reserve(std::size(kKnown));
  for (const auto& k : kKnown) out.push_back({k.bit, k.word, (flags & k.bit) != 0, k.fault});
  return out;
}

}  // namespace hitl::telemetry
