// The one check every number option goes through (issue 19): a value that is not a finite number
// (nan, inf, 1e999), an absurd magnitude, or outside the option's range is refused with a plain
// message ("--actuator-timeout: nan is not a finite number"), never with CLI11's
// "not in range 0.000000 to 179769313486231570814...". add_number_checks() gives it to every number
// option the commands declared without one, so no option is left out; the options that have a
// range say it with positive_number(), non_negative_number() or number_in().
#pragma once

#include <CLI/CLI.hpp>

#include <sstream>
#include <string>
#include <type_traits>

namespace hitl::cli {

/// No number option takes a value larger than this in size (seconds, Hz, metres, percent...).
inline constexpr double kMaxOptionMagnitude = 1e9;

/// Finite, |x| <= kMaxOptionMagnitude, and within [min, max]; `description` is what --help, the
/// man page and the config reference show ("" for none).
CLI::Validator number_check(double min, double max, const std::string& description);

/// > 0 ("POSITIVE").
CLI::Validator positive_number();
/// >= 0 ("NONNEGATIVE").
CLI::Validator non_negative_number();
/// An integer 0 or more, any size (an unsigned option: `--seed -1` would wrap to 2^64 - 1).
CLI::Validator non_negative_integer();

/// Within [min, max], described as CLI::Range describes it ("INT in [1 - 65535]").
template <class T>
CLI::Validator number_in(T min, T max) {
  const std::string type = std::is_integral_v<T> ? "INT" : "FLOAT";
  std::ostringstream d;
  d << type << " in [" << min << " - " << max << "]";
  return number_check(static_cast<double>(min), static_cast<double>(max), d.str());
}

/// Gives every number option of `app` and its subcommands (by its type name: FLOAT, S, HZ, ...;
/// UINT) the plain finite check, after the ones it has.
void add_number_checks(CLI::App& app);

}  // namespace hitl::cli
