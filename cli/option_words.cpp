#include "cli/option_words.h"

#include <map>
#include <cctype>
#include <regex>

#include "cli/value_types.h"

namespace hitl::cli {
namespace {

std::string join(const std::vector<std::string>& items, const std::string& sep) {
  std::string out;
  for (const auto& i : items) out += (out.empty() ? "" : sep) + i;
  return out;
}

/// One CLI11 validator description in words.
std::string check_words(const std::string& check) {
  static const std::map<std::string, std::string> named = {
      {"POSITIVE", "greater than 0"},       {"NONNEGATIVE", "0 or more"},
      {"FILE", "an existing file"},         {"DIR", "an existing directory"},
      {"PATH(existing)", "an existing path"}, {"PATH(non-existing)", "a path that does not exist yet"}};
  if (auto it = named.find(check); it != named.end()) return it->second;
  static const std::regex range(R"(^\w+ in \[(.+) - (.+)\]$)");  // CLI::Range: "INT in [1 - 65535]"
  std::smatch m;
  if (std::regex_match(check, m, range)) return m[1].str() + " to " + m[2].str();
  return check;
}

}  // namespace

std::string option_unit(const OptionModel& o) {
  if (o.is_flag()) return {};
  static const std::map<std::string, std::string> by_type = {
      {"S", "s"}, {"MS", "ms"}, {"HZ", "Hz"}, {"PCT", "%"}, {"M", "m"}, {"M_S", "m/s"}, {"DEG", "deg"}, {"RAD", "rad"}};
  if (auto it = by_type.find(o.type_name); it != by_type.end()) return it->second;
  // "ODOMETRY rate, Hz", "How long lockstep waits ..., s", "..., Hz; 0: none", "..., percent"
  static const std::regex trailing(R"(, (s|ms|Hz|m|m/s|deg|rad|percent)(;|\.|$))");
  std::smatch m;
  if (std::regex_search(o.description, m, trailing)) return m[1].str() == "percent" ? "%" : m[1].str();
  static const std::regex seconds(R"(\b[Ss]econds\b)"), metres(R"(\b[Mm]etres\b)");
  if (std::regex_search(o.description, seconds)) return "s";
  if (std::regex_search(o.description, metres)) return "m";
  return {};
}

std::string option_constraints(const OptionModel& o) {
  if (o.kind == ValueKind::Choice && o.type_name != "BOOLEAN") return "one of " + join(o.choices, ", ");
  std::vector<std::string> words;
  for (const auto& c : o.checks)
    if (c.find('{') == std::string::npos) words.push_back(check_words(c));
  return join(words, "; ");
}

std::string option_accepts(const OptionModel& o) {
  const std::string constraints = option_constraints(o);
  std::string kind;
  if (!o.is_flag() && o.kind != ValueKind::Choice) {
    if (value_type::is_integer(o.type_name)) kind = "an integer";
    else if (value_type::is_floating(o.type_name)) kind = "a number";
  }
  if (kind.empty() || constraints.empty()) return kind + constraints;
  return kind + ", " + constraints;
}

std::string option_metavar(const OptionModel& o) {
  if (!o.positional.empty()) return o.positional;
  if (o.is_flag()) return {};
  if (o.type_name == "BOOLEAN") return "true|false";
  if (o.kind == ValueKind::Choice && !o.choices.empty() && value_type::is_generic(o.type_name)) return join(o.choices, "|");
  if (!value_type::is_generic(o.type_name) || o.long_names.empty()) return o.type_name.empty() ? "VALUE" : o.type_name;
  std::string name = o.long_names.front();
  for (char& c : name) c = c == '-' ? '_' : static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return name;
}

std::string as_sentence(std::string s) {
  while (!s.empty() && (s.back() == ' ' || s.back() == '\n')) s.pop_back();
  if (!s.empty() && s.back() != '.' && s.back() != '!' && s.back() != '?') s += '.';
  return s;
}

std::string option_value_tag(const OptionModel& o) {
  const std::string value = option_metavar(o);
  if (value.empty() || !o.optional_value() || value.front() == '[') return value;
  return "[" + value + "]";
}

std::vector<std::string> option_notes(const OptionModel& o) {
  std::vector<std::string> notes;
  if (const auto c = option_accepts(o); !c.empty()) notes.push_back("Accepts " + c + ".");
  if (!o.default_value.empty()) {
    const auto unit = option_unit(o);
    notes.push_back("Default: " + o.default_value + (unit.empty() || unit == "%" ? unit : " " + unit) + ".");
  }
  if (!o.excludes.empty()) notes.push_back("Not with " + join(o.excludes, ", ") + ".");
  if (o.repeatable && !o.is_flag()) notes.push_back("May be given more than once.");
  if (o.required) notes.push_back("Required.");
  return notes;
}

std::string toml_value_type(const OptionModel& o) {
  if (o.is_flag()) return o.repeatable ? "true / false, or a count" : "true / false";
  if (o.kind == ValueKind::MessageList) return "list of MAVLink message names";
  std::string base;
  const std::string& t = o.type_name;
  if (t == "BOOLEAN") base = "true / false";
  else if (t == "INT" || t == "UINT" || t == "N") base = "integer";
  else if (t == "FLOAT" || t == "S" || t == "MS" || t == "HZ" || t == "PCT" || t == "M") base = "number";
  else if (t == "TEXT" || t == "ENUM" || t.empty()) base = "string";
  else base = "string (" + t + ")";
  if (!o.repeatable) return base;
  const auto word_end = base.find(' ');  // "string (FILE.xml)" -> "strings (FILE.xml)"
  return "list of " + base.insert(word_end == std::string::npos ? base.size() : word_end, "s");
}

}  // namespace hitl::cli
