// Health of a measured stream against what it should carry, in three grades the dashboard colours
// (green, yellow, red) and scripts can test: within 5 % of the expected rate is Good, within 20 %
// Degraded, anything worse, or a stream that went quiet, Bad.
#pragma once

namespace hitl::telemetry {

enum class Health { Good, Degraded, Bad };

inline constexpr double kGoodWithin_pct = 5.0;
inline constexpr double kDegradedWithin_pct = 20.0;
/// A stream with nothing for this long is stale (Bad), whatever its average says.
inline constexpr double kStaleAfter_s = 1.5;

/// |measured - expected| / expected against the two thresholds; Bad when stale or not finite.
/// With no expectation (expected <= 0) only staleness counts.
Health rate_health(double expected_hz, double measured_hz, bool stale);

/// The worse of two (drake's KeepMoreSevere).
constexpr Health worse(Health a, Health b) { return static_cast<int>(a) >= static_cast<int>(b) ? a : b; }

/// "ok", "warn", "bad": the word shown beside the colour (monochrome terminals, capture-pane).
const char* to_string(Health health);

}  // namespace hitl::telemetry
