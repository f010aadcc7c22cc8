// The campaign file read with toml++ (Debian's libtomlplusplus-dev): its parser gives every key and
// value its line, so each refusal says where; hand-written TOML would have been a second parser to fuzz.
#include "engine/campaign/campaign_file.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <regex>
#include <set>

#include <toml++/toml.h>

#include "base/common/bounded_read.h"
#include "engine/campaign/criteria.h"
#include "engine/campaign/flight.h"
#include "engine/campaign/flight_summary.h"
#include "engine/faults/fault_schedule.h"
#include "engine/faults/scenario.h"
#include "engine/hil/session_snapshot.h"
#include "engine/vehicle/trajectory.h"

namespace hitl::campaign {

const char* to_string(Stack stack) {
  switch (stack) {
    case Stack::Target: return "target";
    case Stack::Px4: return "px4";
  }
  return "target";
}

const char* to_string(ExpectKind kind) {
  switch (kind) {
    case ExpectKind::Statustext: return "statustext";
    case ExpectKind::Mode: return "mode";
    case ExpectKind::Event: return "event";
  }
  return "event";
}

const char* to_string(Comparison comparison) {
  switch (comparison) {
    case Comparison::AtMost: return "max";
    case Comparison::AtLeast: return "min";
    case Comparison::Equals: return "equals";
  }
  return "max";
}

namespace {

/// Reads one campaign file: knows its path and folder, and words every refusal the same way.
class Reader {
 public:
  explicit Reader(std::string path) : path_(std::move(path)) {
    folder_ = std::filesystem::path(path_).parent_path();
  }

  Error at(int line, const std::string& key, const std::string& problem) const {
    return Error::input(path_ + ":" + std::to_string(line) + ": " + key + ": " + problem);
  }
  Error at(const toml::node& node, const std::string& key, const std::string& problem) const {
    return at(static_cast<int>(node.source().begin.line), key, problem);
  }

  /// A relative path is the campaign file's folder's.
  std::string resolve(const std::string& as_written) const {
    const std::filesystem::path p(as_written);
    return p.is_absolute() || folder_.empty() ? p.string() : (folder_ / p).lexically_normal().string();
  }

  /// Every key of `table` must be one of `known`.
  Status only_keys(const toml::table& table, const std::string& where, const std::set<std::string>& known) const {
    for (auto&& [key, node] : table) {
      if (known.count(std::string(key.str())) > 0) continue;
      std::string list;
      for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
      return at(static_cast<int>(key.source().begin.line), where.empty() ? std::string(key.str()) : where + "." + std::string(key.str()),
                "unknown key (known here: " + list + ")");
    }
    return Ok{};
  }

  Expected<std::string> string_of(const toml::node& node, const std::string& key) const {
    if (!node.is_string()) return at(node, key, "must be a string");
    return *node.value<std::string>();
  }

  Expected<double> number_of(const toml::node& node, const std::string& key, double low, double high) const {
    if (!node.is_number()) return at(node, key, "must be a number");
    const double v = *node.value<double>();
    if (!std::isfinite(v) || v < low || v > high)
      return at(node, key, "must be between " + number(low) + " and " + number(high) + " (is " + number(v) + ")");
    return v;
  }

  Expected<const toml::array*> array_of(const toml::node& node, const std::string& key) const {
    const auto* a = node.as_array();
    if (a == nullptr) return at(node, key, "must be an array [...]");
    if (a->empty()) return at(node, key, "is empty: the matrix would have no flights");
    if (a->size() > kMaxAxisValues) return at(node, key, "has more than " + std::to_string(kMaxAxisValues) + " values");
    return a;
  }

  static std::string number(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
  }

  /// A name that can stand in a flight's name and the results: letters, digits, - _ .
  Status check_name(const toml::node& node, int line, const std::string& key, const std::string& name) const {
    (void)node;
    const bool ok = !name.empty() && name.size() <= 64 && std::all_of(name.begin(), name.end(), [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '-' || c == '_' || c == '.';
    });
    if (!ok) return at(line, key, "\"" + name + "\" is not a name (1 to 64 letters, digits, '-', '_', '.')");
    return Ok{};
  }

  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::filesystem::path folder_;
};

int line_of(const toml::key& key) { return static_cast<int>(key.source().begin.line); }

/// Why stack = "px4" needs speeds above 0 (hitl sim --px4's --speed 0 refusal, in a campaign's words).
constexpr const char* kPx4SpeedNeeded =
    "stack = \"px4\" runs PX4 in lockstep at a stated factor (PX4_SIM_SPEED_FACTOR, as hitl sim --px4-speed K): give "
    "speeds above 0 (on a 2-core machine K <= 8 keeps PX4's estimator up)";

/// The entries of a table in the file's order (toml++ keeps tables sorted by key).
std::vector<std::pair<const toml::key*, const toml::node*>> in_file_order(const toml::table& table) {
  std::vector<std::pair<const toml::key*, const toml::node*>> entries;
  for (auto&& [key, node] : table) entries.emplace_back(&key, &node);
  std::stable_sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) {
    return a.first->source().begin < b.first->source().begin;
  });
  return entries;
}

/// px4 = "DIR" and px4_params = { NAME = value } of [campaign]: only with stack = "px4". The DIR is
/// found later (find_campaign_px4), so that --px4 DIR can stand in for one this machine lacks.
Status read_px4_keys(const Reader& r, const toml::table& t, Campaign& c) {
  const auto* dir = t.get("px4");
  const auto* params = t.get("px4_params");
  if (!c.px4) {
    if (dir != nullptr) return r.at(*dir, "campaign.px4", "only with stack = \"px4\" (the PX4 SITL build the flights start)");
    if (params != nullptr) return r.at(*params, "campaign.px4_params", "only with stack = \"px4\"");
    return Ok{};
  }
  if (dir != nullptr) {
    auto d = r.string_of(*dir, "campaign.px4");
    if (!d) return d.error();
    if (d->empty()) return r.at(*dir, "campaign.px4", "is empty: a PX4 SITL build folder or a PX4 tree, as hitl sim --px4 DIR");
    c.px4->dir_as_written = *d;
    c.px4->dir = r.resolve(*d);
    c.px4->line = static_cast<int>(dir->source().begin.line);
  }
  if (params == nullptr) return Ok{};
  const auto* table = params->as_table();
  if (table == nullptr) return r.at(*params, "campaign.px4_params", "must be a table { NAME = value, ... } (PX4's parameters, as --px4-param)");
  if (table->size() > kMaxAxisValues)
    return r.at(*params, "campaign.px4_params", "has more than " + std::to_string(kMaxAxisValues) + " parameters");
  for (const auto& [key, value] : in_file_order(*table)) {
    const std::string where = "campaign.px4_params." + std::string(key->str());
    std::string text;
    if (value->is_integer()) text = std::to_string(*value->value<int64_t>());
    else if (value->is_floating_point()) {
      const double v = *value->value<double>();
      if (!std::isfinite(v)) return r.at(*value, where, "must be a finite number");
      char number[32];
      std::snprintf(number, sizeof number, "%.9g", v);
      text = number;
    } else {
      return r.at(*value, where, "must be a number (PX4 parameters are whole numbers or decimals)");
    }
    auto p = px4::parse_px4_param(std::string(key->str()) + "=" + text);
    if (!p) return r.at(line_of(*key), where, p.error().message);
    c.px4->params.push_back(*p);
  }
  return Ok{};
}

Status read_campaign_table(const Reader& r, const toml::table& root, Campaign& c) {
  const auto* node = root.get("campaign");
  if (node == nullptr) return r.at(1, "campaign", "missing: the file needs a [campaign] table with its name");
  const auto* t = node->as_table();
  if (t == nullptr) return r.at(*node, "campaign", "must be a table [campaign]");
  if (auto ok = r.only_keys(*t, "campaign", {"name", "stack", "px4", "px4_params", "time_limit_s", "sim_limit_s", "report"}); !ok)
    return ok;
  const auto* name = t->get("name");
  if (name == nullptr) return r.at(*node, "campaign.name", "missing: the campaign's name");
  auto n = r.string_of(*name, "campaign.name");
  if (!n) return n.error();
  if (auto ok = r.check_name(*name, static_cast<int>(name->source().begin.line), "campaign.name", *n); !ok) return ok;
  c.name = *n;
  if (const auto* stack = t->get("stack")) {
    auto s = r.string_of(*stack, "campaign.stack");
    if (!s) return s.error();
    if (*s == "px4") {
      c.stack = Stack::Px4;
      c.px4.emplace();
      c.px4->line = static_cast<int>(stack->source().begin.line);
    } else if (*s != "target") {
      return r.at(*stack, "campaign.stack", "\"" + *s + "\" is not a flight stack (known: target, px4)");
    }
  }
  if (auto ok = read_px4_keys(r, *t, c); !ok) return ok;
  if (const auto* v = t->get("time_limit_s")) {
    auto x = r.number_of(*v, "campaign.time_limit_s", 0.1, 86400);
    if (!x) return x.error();
    c.time_limit_s = *x;
  }
  if (const auto* v = t->get("sim_limit_s")) {
    auto x = r.number_of(*v, "campaign.sim_limit_s", 0, 86400);
    if (!x) return x.error();
    c.sim_limit_s = *x;
  }
  if (const auto* v = t->get("report")) {
    if (!v->is_boolean()) return r.at(*v, "campaign.report", "must be true or false");
    c.report = *v->value<bool>();
  }
  return Ok{};
}

Status read_matrix(const Reader& r, const toml::table& root, Campaign& c) {
  const auto* node = root.get("matrix");
  if (node == nullptr) return r.at(1, "matrix", "missing: the file needs a [matrix] table with its trajectories");
  const auto* t = node->as_table();
  if (t == nullptr) return r.at(*node, "matrix", "must be a table [matrix]");
  if (auto ok = r.only_keys(*t, "matrix", {"trajectories", "seeds", "speeds"}); !ok) return ok;
  const auto* trajectories = t->get("trajectories");
  if (trajectories == nullptr) return r.at(*node, "matrix.trajectories", "missing: at least one trajectory file");
  auto a = r.array_of(*trajectories, "matrix.trajectories");
  if (!a) return a.error();
  std::set<std::string> seen;
  for (std::size_t i = 0; i < (*a)->size(); ++i) {
    const auto& v = *(*a)->get(i);
    const std::string key = "matrix.trajectories[" + std::to_string(i) + "]";
    auto s = r.string_of(v, key);
    if (!s) return s.error();
    TrajectoryValue tv;
    tv.as_written = *s;
    tv.path = r.resolve(*s);
    tv.name = std::filesystem::path(*s).stem().string();
    if (!seen.insert(tv.name).second) return r.at(v, key, "a second trajectory named \"" + tv.name + "\" (file names must differ)");
    if (auto loaded = vehicle::Trajectory::load(tv.path); !loaded) return r.at(v, key, loaded.error().message);
    c.trajectories.push_back(std::move(tv));
  }
  if (const auto* seeds = t->get("seeds")) {
    auto sa = r.array_of(*seeds, "matrix.seeds");
    if (!sa) return sa.error();
    for (std::size_t i = 0; i < (*sa)->size(); ++i) {
      const auto& v = *(*sa)->get(i);
      const std::string key = "matrix.seeds[" + std::to_string(i) + "]";
      if (!v.is_integer() || *v.value<int64_t>() < 0) return r.at(v, key, "must be a whole number >= 0");
      const auto seed = static_cast<uint64_t>(*v.value<int64_t>());
      if (std::find(c.seeds.begin(), c.seeds.end(), seed) != c.seeds.end())
        return r.at(v, key, "seed " + std::to_string(seed) + " is listed twice");
      c.seeds.push_back(seed);
    }
  } else {
    c.seeds = {1};
  }
  if (const auto* speeds = t->get("speeds")) {
    auto sa = r.array_of(*speeds, "matrix.speeds");
    if (!sa) return sa.error();
    for (std::size_t i = 0; i < (*sa)->size(); ++i) {
      auto x = r.number_of(*(*sa)->get(i), "matrix.speeds[" + std::to_string(i) + "]", 0, 1000);
      if (!x) return x.error();
      if (c.stack == Stack::Px4 && !(*x > 0)) return r.at(*(*sa)->get(i), "matrix.speeds[" + std::to_string(i) + "]", kPx4SpeedNeeded);
      if (std::find(c.speeds.begin(), c.speeds.end(), *x) != c.speeds.end())
        return r.at(*(*sa)->get(i), "matrix.speeds[" + std::to_string(i) + "]", "speed " + Reader::number(*x) + " is listed twice");
      c.speeds.push_back(*x);
    }
  } else {
    if (c.stack == Stack::Px4) return r.at(*node, "matrix.speeds", std::string("missing: ") + kPx4SpeedNeeded);
    c.speeds = {0};
  }
  return Ok{};
}

Status read_fault_case(const Reader& r, const toml::key& key, const toml::node& node, const faults::Suggest& suggest,
                       FaultCase& fc) {
  const std::string where = "faults." + std::string(key.str());
  fc.name = std::string(key.str());
  if (auto ok = r.check_name(node, line_of(key), where, fc.name); !ok) return ok;
  const toml::array* specs = node.as_array();
  if (const auto* t = node.as_table()) {
    if (auto ok = r.only_keys(*t, where, {"faults", "scenario"}); !ok) return ok;
    if (const auto* f = t->get("faults")) {
      specs = f->as_array();
      if (specs == nullptr) return r.at(*f, where + ".faults", "must be an array of --fault specs");
    }
    if (const auto* s = t->get("scenario")) {
      auto text = r.string_of(*s, where + ".scenario");
      if (!text) return text.error();
      fc.scenario_as_written = *text;
      fc.scenario = r.resolve(*text);
    }
  } else if (specs == nullptr) {
    return r.at(node, where, "must be an array of --fault specs ([] for none) or a table { faults = [...], scenario = \"FILE\" }");
  }
  if (specs != nullptr) {
    if (specs->size() > kMaxAxisValues) return r.at(node, where, "has more than " + std::to_string(kMaxAxisValues) + " faults");
    for (std::size_t i = 0; i < specs->size(); ++i) {
      const auto& v = *specs->get(i);
      const std::string k = where + "[" + std::to_string(i) + "]";
      auto text = r.string_of(v, k);
      if (!text) return text.error();
      auto spec = faults::parse_fault(*text, suggest);
      if (!spec) return r.at(v, k, spec.error().message);
      fc.specs.push_back(*text);
      fc.faults.push_back(*spec);
    }
  }
  if (!fc.scenario.empty()) {
    auto scenario = faults::load_scenario(fc.scenario, suggest);
    if (!scenario) return r.at(node, where + ".scenario", scenario.error().message);
    fc.faults.insert(fc.faults.end(), scenario->begin(), scenario->end());
  }
  if (fc.name == "none" && !fc.faults.empty()) return r.at(node, where, "the case \"none\" is the flight without faults: give it []");
  if (auto limit = faults::check_active_limit(fc.faults); !limit) return r.at(node, where, limit.error().message);
  return Ok{};
}

Status read_faults(const Reader& r, const toml::table& root, const faults::Suggest& suggest, Campaign& c) {
  const auto* node = root.get("faults");
  if (node == nullptr) {
    c.fault_cases.push_back(FaultCase{"none", {}, {}, {}, {}});
    return Ok{};
  }
  const auto* t = node->as_table();
  if (t == nullptr) return r.at(*node, "faults", "must be a table [faults] of named cases");
  if (t->empty()) return r.at(*node, "faults", "has no cases: the matrix would have no flights (none = [] is the flight without faults)");
  if (t->size() > kMaxAxisValues) return r.at(*node, "faults", "has more than " + std::to_string(kMaxAxisValues) + " cases");
  std::map<std::string, std::string> seen;  // what a case flies -> its name: two names for one case would be one flight twice
  for (const auto& [key, value] : in_file_order(*t)) {
    FaultCase fc;
    if (auto ok = read_fault_case(r, *key, *value, suggest, fc); !ok) return ok;
    std::string flies = "scenario=" + fc.scenario_as_written + ";";
    for (const auto& f : fc.faults) flies += f.text() + ";";
    if (const auto it = seen.find(flies); it != seen.end())
      return r.at(line_of(*key), "faults." + fc.name, "the same faults as faults." + it->second + " (each case must differ)");
    seen.emplace(flies, fc.name);
    c.fault_cases.push_back(std::move(fc));
  }
  return Ok{};
}

Status read_criteria(const Reader& r, const toml::table& root, Campaign& c) {
  const auto* node = root.get("criteria");
  if (node == nullptr) return Ok{};
  const auto* t = node->as_table();
  if (t == nullptr) return r.at(*node, "criteria", "must be a table [criteria] of named criteria");
  if (t->size() > kMaxAxisValues) return r.at(*node, "criteria", "has more than " + std::to_string(kMaxAxisValues) + " criteria");
  const auto figures = criterion_figures();
  for (const auto& [key, value] : in_file_order(*t)) {
    const std::string where = "criteria." + std::string(key->str());
    Criterion cr;
    cr.name = std::string(key->str());
    cr.line = line_of(*key);
    if (auto ok = r.check_name(*value, cr.line, where, cr.name); !ok) return ok;
    if (cr.name == kFlownCriterion) return r.at(cr.line, where, "\"flown\" is the criterion every flight has; name this one otherwise");
    const auto* ct = value->as_table();
    if (ct == nullptr) return r.at(*value, where, "must be a table { figure = \"PATH\", max = N } (or min, equals)");
    if (auto ok = r.only_keys(*ct, where, {"figure", "max", "min", "equals"}); !ok) return ok;
    const auto* figure = ct->get("figure");
    if (figure == nullptr) return r.at(*value, where + ".figure", "missing: the summary figure to judge (docs/campaigns.md)");
    auto f = r.string_of(*figure, where + ".figure");
    if (!f) return f.error();
    if (std::find(figures.begin(), figures.end(), *f) == figures.end())
      return r.at(*figure, where + ".figure", "\"" + *f + "\" is not a figure of a flight's summary (docs/campaigns.md lists them)");
    cr.figure = *f;
    int given = 0;
    for (const char* op : {"max", "min", "equals"})
      if (ct->get(op) != nullptr) ++given;
    if (given != 1) return r.at(*value, where, "needs exactly one of max, min, equals");
    if (const auto* at_most = ct->get("max")) {
      auto x = r.number_of(*at_most, where + ".max", -1e300, 1e300);
      if (!x) return x.error();
      cr.comparison = Comparison::AtMost;
      cr.limit = *x;
    } else if (const auto* at_least = ct->get("min")) {
      auto x = r.number_of(*at_least, where + ".min", -1e300, 1e300);
      if (!x) return x.error();
      cr.comparison = Comparison::AtLeast;
      cr.limit = *x;
    } else if (const auto* equals = ct->get("equals")) {
      cr.comparison = Comparison::Equals;
      if (equals->is_boolean()) {
        cr.equals_bool = *equals->value<bool>();
      } else if (equals->is_string()) {
        cr.equals_text = *equals->value<std::string>();
      } else {
        auto x = r.number_of(*equals, where + ".equals", -1e300, 1e300);
        if (!x) return r.at(*equals, where + ".equals", "must be a number, true/false or a string");
        cr.limit = *x;
      }
    }
    c.criteria.push_back(std::move(cr));
  }
  return Ok{};
}

Status read_expectations(const Reader& r, const toml::table& root, const std::set<std::string>& names_taken, Campaign& c) {
  const auto* node = root.get("expect");
  if (node == nullptr) return Ok{};
  const auto* t = node->as_table();
  if (t == nullptr) return r.at(*node, "expect", "must be a table [expect] of named expectations");
  if (t->size() > kMaxAxisValues) return r.at(*node, "expect", "has more than " + std::to_string(kMaxAxisValues) + " expectations");
  const auto fault_names = faults::fault_names();
  for (const auto& [key, value] : in_file_order(*t)) {
    const std::string where = "expect." + std::string(key->str());
    Expectation e;
    e.name = std::string(key->str());
    e.line = line_of(*key);
    if (auto ok = r.check_name(*value, e.line, where, e.name); !ok) return ok;
    if (e.name == kFlownCriterion || names_taken.count(e.name) > 0)
      return r.at(e.line, where, "\"" + e.name + "\" is already a criterion's name; each result needs its own");
    const auto* et = value->as_table();
    if (et == nullptr) return r.at(*value, where, "must be a table { statustext = \"REGEX\" } (or mode, event; after_fault, within_s)");
    if (auto ok = r.only_keys(*et, where, {"statustext", "mode", "event", "after_fault", "within_s"}); !ok) return ok;
    int given = 0;
    for (const char* kind : {"statustext", "mode", "event"})
      if (et->get(kind) != nullptr) ++given;
    if (given != 1) return r.at(*value, where, "needs exactly one of statustext, mode, event");
    const char* kind_key = et->get("statustext") != nullptr ? "statustext" : et->get("mode") != nullptr ? "mode" : "event";
    e.kind = et->get("statustext") != nullptr ? ExpectKind::Statustext : et->get("mode") != nullptr ? ExpectKind::Mode : ExpectKind::Event;
    const auto& pattern_node = *et->get(kind_key);
    auto pattern = r.string_of(pattern_node, where + "." + kind_key);
    if (!pattern) return pattern.error();
    if (pattern->empty() || pattern->size() > kMaxPatternChars)
      return r.at(pattern_node, where + "." + kind_key, "must be 1 to " + std::to_string(kMaxPatternChars) + " characters");
    if (e.kind != ExpectKind::Mode) {
      try {
        std::regex check(*pattern, std::regex::ECMAScript);
      } catch (const std::regex_error& error) {
        return r.at(pattern_node, where + "." + kind_key, "not a regular expression: " + std::string(error.what()));
      }
    }
    e.pattern = *pattern;
    if (const auto* after = et->get("after_fault")) {
      auto f = r.string_of(*after, where + ".after_fault");
      if (!f) return f.error();
      if (std::find(fault_names.begin(), fault_names.end(), *f) == fault_names.end())
        return r.at(*after, where + ".after_fault", "\"" + *f + "\" is not a fault (docs/faults.md)");
      e.after_fault = *f;
    }
    if (const auto* within = et->get("within_s")) {
      auto x = r.number_of(*within, where + ".within_s", 0, 86400);
      if (!x) return x.error();
      e.within_s = *x;
    }
    c.expectations.push_back(std::move(e));
  }
  return Ok{};
}

void collect_leaves(const nlohmann::json& j, const std::string& prefix, std::vector<std::string>& out) {
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string path = prefix.empty() ? it.key() : prefix + "." + it.key();
    if (it->is_object()) collect_leaves(*it, path, out);
    else if (it->is_number() || it->is_boolean() || it->is_null() || it->is_string()) out.push_back(path);
  }
}

}  // namespace

std::vector<std::string> criterion_figures() {
  Campaign c;
  hil::SessionSnapshot s;
  s.trajectory_state = "DONE";  // the trajectory's figures are in every campaign flight's summary
  auto j = flight_summary_json(c, Flight{}, s, "trajectory_done", StackFigures{}, nullptr);
  j.erase("flight");  // its parameters, not figures
  j.erase("type");
  std::vector<std::string> out;
  collect_leaves(j, "", out);
  return out;
}

Status find_campaign_px4(Campaign& c, const std::string& override_dir) {
  if (c.stack != Stack::Px4) {
    if (!override_dir.empty())
      return Error::usage("--px4: " + c.file + " flies against stack = \"" + to_string(c.stack) + "\"; --px4 DIR is for stack = \"px4\"");
    return Ok{};
  }
  std::string dir, where;
  if (!override_dir.empty()) {
    dir = override_dir;
    where = "--px4: ";
  } else if (!c.px4->dir.empty()) {
    dir = c.px4->dir;
    where = c.file + ":" + std::to_string(c.px4->line) + ": campaign.px4: ";
  } else {
    return Error::input(c.file + ":" + std::to_string(c.px4->line) +
                        ": campaign.px4: missing: stack = \"px4\" needs px4 = \"DIR\" (a PX4 SITL build folder or a PX4 tree, "
                        "as hitl sim --px4 DIR) or --px4 DIR");
  }
  auto build = px4::find_px4_build(dir);
  if (!build) return build.error().prefixed(where);
  if (!build->lockstep)
    return Error::input(where + "'" + build->build_dir + "' is a PX4 build without lockstep (px4_sitl_nolockstep); campaigns "
                        "need px4_sitl_default, which scripts/px4-sitl.sh builds");
  c.px4->build = std::move(build.value());
  return Ok{};
}

std::string stack_version(const Campaign& c) {
  return c.px4 && c.px4->build ? c.px4->build->version : std::string();
}

Expected<Campaign> parse_campaign(const std::string& text, const std::string& path, const faults::Suggest& suggest) {
  const Reader r(path);
  toml::table root;
  try {
    root = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    return Error::input(path + ":" + std::to_string(e.source().begin.line) + ": " + std::string(e.description()));
  }
  Campaign c;
  c.file = path;
  if (auto ok = r.only_keys(root, "", {"campaign", "matrix", "faults", "criteria", "expect"}); !ok) return ok.error();
  if (auto ok = read_campaign_table(r, root, c); !ok) return ok.error();
  if (auto ok = read_matrix(r, root, c); !ok) return ok.error();
  if (auto ok = read_faults(r, root, suggest, c); !ok) return ok.error();
  if (auto ok = read_criteria(r, root, c); !ok) return ok.error();
  std::set<std::string> criterion_names;
  for (const auto& cr : c.criteria) criterion_names.insert(cr.name);
  if (auto ok = read_expectations(r, root, criterion_names, c); !ok) return ok.error();
  const std::size_t flights = c.trajectories.size() * c.fault_cases.size() * c.seeds.size() * c.speeds.size();
  if (flights > kMaxFlights)
    return Error::input(path + ": the matrix has " + std::to_string(flights) + " flights, more than " + std::to_string(kMaxFlights));
  return c;
}

Expected<Campaign> load_campaign(const std::string& path, const faults::Suggest& suggest) {
  auto text = read_bounded_file(path, "campaign file", kMaxCampaignFileBytes);
  if (!text) return text.error();
  return parse_campaign(*text, path, suggest);
}

}  // namespace hitl::campaign
