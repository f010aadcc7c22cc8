// The allowed interval of a config file's number (config_fields.h reads and checks it), apart from
// the JSON machinery so that a field table outside engine/model (a sensor unit's keys,
// engine/sensors/unit.h) can state its ranges without it.
#pragma once

#include <cmath>
#include <sstream>
#include <string>

namespace hitl::model::config_fields {

/// An allowed interval for a number, and how to say it in an error.
struct Range {
  enum class Kind { Any, Positive, NonNegative, Closed };
  Kind kind = Kind::Any;
  double lo = 0.0;
  double hi = 0.0;

  bool contains(double v) const {
    switch (kind) {
      case Kind::Any: return std::isfinite(v);
      case Kind::Positive: return v > 0.0 && std::isfinite(v);
      case Kind::NonNegative: return v >= 0.0 && std::isfinite(v);
      case Kind::Closed: return v >= lo && v <= hi;
    }
    return false;
  }
  std::string describe() const {
    switch (kind) {
      case Kind::Any: return "must be a finite number";
      case Kind::Positive: return "must be > 0";
      case Kind::NonNegative: return "must be >= 0";
      case Kind::Closed: {
        std::ostringstream s;
        s << "must be in [" << lo << ", " << hi << "]";
        return s.str();
      }
    }
    return {};
  }
};
constexpr Range kAny{};
constexpr Range kPositive{Range::Kind::Positive};
constexpr Range kNonNegative{Range::Kind::NonNegative};
constexpr Range closed(double lo, double hi) { return {Range::Kind::Closed, lo, hi}; }

}  // namespace hitl::model::config_fields
