#include "engine/telemetry/imu_noise_statement.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace hitl::telemetry {
namespace {

constexpr std::string_view kOpening = "imu noise";
constexpr std::size_t kMaxProfileName = 64;
/// No IMU's noise figure comes near this; a larger one is not a statement (and prints back whole).
constexpr double kMaxFigure = 1e6;

std::string figure(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.5g", v);
  return text;
}

bool take(std::string_view text, std::size_t& at, std::string_view word) {
  if (text.substr(at, word.size()) != word) return false;
  at += word.size();
  return true;
}

/// A number in [0, kMaxFigure] at `at` (no sign, no spaces), moved past.
std::optional<double> number_at(std::string_view text, std::size_t& at) {
  std::size_t end = at;
  while (end < text.size() && end - at < 32 && (std::isdigit(static_cast<unsigned char>(text[end])) || text[end] == '.' ||
                                                text[end] == 'e' || text[end] == 'E' || text[end] == '-' || text[end] == '+'))
    ++end;
  if (end == at || text[at] == '-' || text[at] == '+') return std::nullopt;
  const std::string digits(text.substr(at, end - at));
  char* parsed_end = nullptr;
  const double v = std::strtod(digits.c_str(), &parsed_end);
  if (parsed_end != digits.c_str() + digits.size() || !std::isfinite(v) || v < 0.0 || v > kMaxFigure) return std::nullopt;
  at = end;
  return v;
}

}  // namespace

std::string imu_noise_statement(const ImuNoiseFigures& f) {
  return std::string(kOpening) + (f.profile.empty() ? "" : " (profile " + f.profile + ")") + ": gyro N " +
         figure(f.gyro_noise_density) + " rad/s/sqrt(Hz) B " + figure(f.gyro_bias_instability) + " rad/s, accel N " +
         figure(f.accel_noise_density) + " m/s^2/sqrt(Hz) B " + figure(f.accel_bias_instability) + " m/s^2";
}

std::optional<ImuNoiseFigures> parse_imu_noise_statement(std::string_view text) {
  std::size_t at = 0;
  ImuNoiseFigures f;
  if (!take(text, at, kOpening)) return std::nullopt;
  if (take(text, at, " (profile ")) {
    const std::size_t close = text.find(')', at);
    if (close == std::string_view::npos || close == at || close - at > kMaxProfileName) return std::nullopt;
    for (char c : text.substr(at, close - at))
      if (!(std::islower(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '.' || c == '_'))
        return std::nullopt;
    f.profile = std::string(text.substr(at, close - at));
    at = close + 1;
  }
  struct Field {
    std::string_view before;
    double* value;
  };
  const Field fields[] = {{": gyro N ", &f.gyro_noise_density},
                          {" rad/s/sqrt(Hz) B ", &f.gyro_bias_instability},
                          {" rad/s, accel N ", &f.accel_noise_density},
                          {" m/s^2/sqrt(Hz) B ", &f.accel_bias_instability}};
  for (const Field& field : fields) {
    if (!take(text, at, field.before)) return std::nullopt;
    const auto v = number_at(text, at);
    if (!v) return std::nullopt;
    *field.value = *v;
  }
  if (!take(text, at, " m/s^2") || at != text.size()) return std::nullopt;
  return f;
}

}  // namespace hitl::telemetry
