#include "cli/number_check.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>

#include "cli/value_types.h"

namespace hitl::cli {
namespace {

std::string plain(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", x);
  return text;
}

/// "" when `text` is a finite number of sane size within [min, max], else why not.
std::string refuse(const std::string& text, double min, double max) {
  const char* begin = text.c_str();
  char* end = nullptr;
  const double x = std::strtod(begin, &end);
  if (end == begin || *end != '\0') return "'" + text + "' is not a number";
  if (!std::isfinite(x)) return text + " is not a finite number";
  if (std::fabs(x) > kMaxOptionMagnitude) return text + " is too large (at most " + plain(kMaxOptionMagnitude) + " in size)";
  if (x < min) return text + " is below " + plain(min);
  if (x > max) return text + " is above " + plain(max);
  return {};
}


}  // namespace

CLI::Validator number_check(double min, double max, const std::string& description) {
  return CLI::Validator([min, max](std::string& input) { return refuse(input, min, max); }, description);
}

CLI::Validator positive_number() {
  return CLI::Validator(
      [](std::string& input) {
        auto why = refuse(input, -kMaxOptionMagnitude, kMaxOptionMagnitude);
        if (why.empty() && std::strtod(input.c_str(), nullptr) <= 0) why = input + " is not greater than 0";
        return why;
      },
      "POSITIVE");
}

CLI::Validator non_negative_number() { return number_check(0, kMaxOptionMagnitude, "NONNEGATIVE"); }

CLI::Validator non_negative_integer() {
  return CLI::Validator(
      [](std::string& input) {
        const auto first = input.find_first_not_of(" \t");
        return first != std::string::npos && input[first] == '-' ? input + " is negative; give 0 or more" : std::string{};
      },
      "");
}

void add_number_checks(CLI::App& app) {
  for (CLI::Option* o : app.get_options()) {
    if (o->get_expected_max() == 0) continue;  // a flag
    std::string type = o->get_type_name();  // "FLOAT:POSITIVE": the type, then the checks' descriptions
    type = type.substr(0, type.find(':'));
    if (value_type::is_floating(type)) o->check(number_check(-kMaxOptionMagnitude, kMaxOptionMagnitude, ""));
    else if (type == "UINT") o->check(non_negative_integer());
  }
  for (CLI::App* sub : app.get_subcommands({})) add_number_checks(*sub);
}

}  // namespace hitl::cli
