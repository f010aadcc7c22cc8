#include "engine/faults/scenario.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <nlohmann/json.hpp>

#include "base/common/bounded_read.h"
#include "base/common/json_nesting.h"
#include "engine/faults/fault_schedule.h"

namespace hitl::faults {
namespace {

using nlohmann::json;

/// A value as the file has it, for an error message: at most a line (depth is bounded before).
std::string shown(const json& v) {
  constexpr std::size_t kMaxShown = 60;
  std::string text = v.dump(-1, ' ', false, json::error_handler_t::replace);
  if (text.size() > kMaxShown) text = text.substr(0, kMaxShown) + "...";
  return text;
}

Expected<double> number_field(const json& event, const char* key, const std::string& where) {
  const json& v = event.at(key);
  if (!v.is_number()) return Error::input(where + "." + key + ": must be a number (got " + shown(v) + ")");
  return v.get<double>();
}

Expected<std::vector<double>> args_field(const json& v, const std::string& where) {
  std::vector<double> args;
  if (v.is_array()) {
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (!v[i].is_number()) return Error::input(where + ".args[" + std::to_string(i) + "]: must be a number (got " + shown(v[i]) + ")");
      args.push_back(v[i].get<double>());
    }
    return args;
  }
  if (!v.is_string()) return Error::input(where + ".args: must be an array of numbers or a string \"2,0.6\" (got " + shown(v) + ")");
  const std::string list = v.get<std::string>();
  if (list.empty()) return args;
  std::size_t pos = 0;
  for (;;) {
    const auto comma = list.find(',', pos);
    auto n = parse_number(list.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos),
                          where + ".args: argument " + std::to_string(args.size() + 1));
    if (!n) return n.error();
    args.push_back(*n);
    if (comma == std::string::npos) return args;
    pos = comma + 1;
  }
}

constexpr double kMaxAltitude_m = 100000;
constexpr double kMaxDelay_s = 86400;
constexpr std::size_t kMaxNameLength = 64;

Expected<Condition> parse_condition(const json& c, const std::string& where) {
  if (!c.is_object())
    return Error::input(where + ": must be an object {\"altitude_above_m\", \"armed\", \"mode\", \"after\", \"delay_s\"} (got " + shown(c) + ")");
  Condition out;
  for (const auto& [key, value] : c.items()) {
    const std::string at = where + "." + key;
    if (key == "altitude_above_m" || key == "altitude_below_m" || key == "delay_s") {
      if (!value.is_number()) return Error::input(at + ": must be a number (got " + shown(value) + ")");
      const double v = value.get<double>();
      const double lo = key == "delay_s" ? 0 : -kMaxAltitude_m, hi = key == "delay_s" ? kMaxDelay_s : kMaxAltitude_m;
      if (!std::isfinite(v) || v < lo || v > hi) return Error::input(at + ": must be within " + std::to_string(static_cast<long>(lo)) + ".." + std::to_string(static_cast<long>(hi)) + " (got " + shown(value) + ")");
      (key == "delay_s" ? out.delay_s : key == "altitude_above_m" ? out.altitude_above_m.emplace() : out.altitude_below_m.emplace()) = v;
    } else if (key == "armed") {
      if (!value.is_boolean()) return Error::input(at + ": must be true or false (got " + shown(value) + ")");
      out.armed = value.get<bool>();
    } else if (key == "mode" || key == "after") {
      if (!value.is_string() || value.get<std::string>().empty() || value.get<std::string>().size() > kMaxNameLength)
        return Error::input(at + ": must be a name of 1.." + std::to_string(kMaxNameLength) + " characters (got " + shown(value) + ")");
      (key == "mode" ? out.mode : out.after) = value.get<std::string>();
    } else {
      return Error::input(where + ": unknown key '" + key + "' (a condition has altitude_above_m, altitude_below_m, armed, mode, after, delay_s)");
    }
  }
  if (!out.altitude_above_m && !out.altitude_below_m && !out.armed && !out.mode && !out.after)
    return Error::input(where + ": names nothing to wait for (altitude_above_m, altitude_below_m, armed, mode or after)");
  return out;
}

Expected<FaultSpec> parse_event(const json& event, const std::string& where, const Suggest& suggest) {
  if (!event.is_object()) return Error::input(where + ": must be an object {\"at_s\", \"fault\", ...} (got " + shown(event) + ")");
  for (const auto& [key, value] : event.items())
    if (key != "at_s" && key != "fault" && key != "args" && key != "duration_s" && key != "id" && key != "when" && key != "end_when")
      return Error::input(where + ": unknown key '" + key + "' (an event has id, at_s, when, fault, args, duration_s, end_when)");
  if (!event.contains("fault")) return Error::input(where + ": no \"fault\"");
  if (!event.contains("at_s") && !event.contains("when"))
    return Error::input(where + ": no \"at_s\" (the start, simulated seconds) and no \"when\" (a condition)");
  if (!event.at("fault").is_string()) return Error::input(where + ".fault: must be a fault's name (got " + shown(event.at("fault")) + ")");
  const std::string name = event.at("fault").get<std::string>();
  Expected<double> at = 0.0;
  if (event.contains("at_s")) at = number_field(event, "at_s", where);
  if (!at) return at.error();
  std::string id;
  if (event.contains("id")) {
    const json& v = event.at("id");
    if (!v.is_string() || v.get<std::string>().empty() || v.get<std::string>().size() > kMaxNameLength)
      return Error::input(where + ".id: must be a name of 1.." + std::to_string(kMaxNameLength) + " characters (got " + shown(v) + ")");
    id = v.get<std::string>();
  }
  std::optional<Condition> start_when, end_when;
  if (event.contains("when")) {
    auto c = parse_condition(event.at("when"), where + ".when");
    if (!c) return c.error();
    start_when = *c;
  }
  if (event.contains("end_when")) {
    auto c = parse_condition(event.at("end_when"), where + ".end_when");
    if (!c) return c.error();
    end_when = *c;
  }
  std::optional<double> duration_s;
  if (event.contains("duration_s")) {
    auto d = number_field(event, "duration_s", where);
    if (!d) return d.error();
    duration_s = *d;
  }
  std::vector<double> args;
  if (event.contains("args")) {
    auto a = args_field(event.at("args"), where);
    if (!a) return a.error();
    args = std::move(a.value());
  }
  auto spec = make_fault(name, args, *at, duration_s, suggest);
  if (!spec) return spec.error().prefixed(where + ": ");
  spec->id = id;
  spec->start_when = start_when;
  spec->end_when = end_when;
  return spec;
}

/// The events that wait on each other through "after" (a cycle: none of them would ever start),
/// as "events 'a', 'b' wait on each other ('a' after 'b', 'b' after 'a')"; "" when none do.
std::string start_cycle(const std::vector<FaultSpec>& specs) {
  // Each event waits for at most one other to start (its when.after): follow the chain from each.
  auto waits_for = [&](std::size_t i) -> std::optional<std::size_t> {
    if (!specs[i].start_when || !specs[i].start_when->after) return std::nullopt;
    for (std::size_t j = 0; j < specs.size(); ++j)
      if (specs[j].id == *specs[i].start_when->after) return j;
    return std::nullopt;
  };
  std::vector<int> state(specs.size(), 0);  // 0 unvisited, 1 on the current chain, 2 done
  for (std::size_t first = 0; first < specs.size(); ++first) {
    std::vector<std::size_t> chain;
    std::optional<std::size_t> at = first;
    while (at && state[*at] == 0) {
      state[*at] = 1;
      chain.push_back(*at);
      at = waits_for(*at);
    }
    if (at && state[*at] == 1) {  // back on this chain: a cycle from *at to the chain's end
      std::vector<std::size_t> cycle(std::find(chain.begin(), chain.end(), *at), chain.end());
      std::sort(cycle.begin(), cycle.end());
      std::string names, edges;
      for (std::size_t k = 0; k < cycle.size(); ++k) {
        const FaultSpec& s = specs[cycle[k]];
        names += (k ? ", '" : "'") + s.id + "'";
        edges += (k ? ", '" : "'") + s.id + "' after '" + *s.start_when->after + "'";
      }
      return "events " + names + " wait on each other (" + edges + "): none would start";
    }
    for (std::size_t i : chain) state[i] = 2;
  }
  return "";
}

Expected<std::vector<FaultSpec>> parse_events(const std::string& text, const std::string& where, const Suggest& suggest) {
  if (auto depth = check_json_depth(text, where); !depth) return depth.error();
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::exception& e) {  // parse_error, and out_of_range for a number like 1e400
    return Error::input(where + ": not JSON: " + e.what());
  }
  if (!doc.is_object() || !doc.contains("events"))
    return Error::input(where + ": must be an object {\"events\": [...]} (docs/faults.md \"Scenario files\")");
  for (const auto& [key, value] : doc.items())
    if (key != "events" && key != "description")
      return Error::input(where + ": unknown key '" + key + "' (a scenario has events and description)");
  if (doc.contains("description") && !doc.at("description").is_string())
    return Error::input(where + ".description: must be a string");
  const json& events = doc.at("events");
  if (!events.is_array()) return Error::input(where + ".events: must be an array of events");
  if (events.size() > kMaxScenarioEvents)
    return Error::input(where + ".events: more than " + std::to_string(kMaxScenarioEvents) + " events");
  std::vector<FaultSpec> specs;
  for (std::size_t i = 0; i < events.size(); ++i) {
    auto spec = parse_event(events[i], where + ": events[" + std::to_string(i) + "]", suggest);
    if (!spec) return spec.error();
    specs.push_back(std::move(spec.value()));
  }
  // Names: each once; every "after" names an event of this file.
  for (std::size_t i = 0; i < specs.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j)
      if (!specs[i].id.empty() && specs[i].id == specs[j].id)
        return Error::input(where + ": events[" + std::to_string(i) + "].id: '" + specs[i].id + "' is events[" + std::to_string(j) + "]'s too");
    for (const auto* c : {&specs[i].start_when, &specs[i].end_when}) {
      if (!*c || !(*c)->after) continue;
      bool found = false;
      for (const auto& other : specs) found = found || other.id == *(*c)->after;
      if (!found || *(*c)->after == specs[i].id)
        return Error::input(where + ": events[" + std::to_string(i) + "]: \"after\": '" + *(*c)->after + "' is no other event's id");
    }
  }
  if (const std::string cycle = start_cycle(specs); !cycle.empty()) return Error::input(where + ": " + cycle);
  if (auto overlap = check_active_limit(specs); !overlap) return overlap.error().prefixed(where + ": ");
  return specs;
}

}  // namespace

Expected<std::vector<FaultSpec>> parse_scenario(const std::string& text, const std::string& where, const Suggest& suggest) {
  auto specs = parse_events(text, where, suggest);
  if (!specs) return Error::input(specs.error().message);  // everything wrong here is the file's
  return specs;
}

Expected<std::vector<FaultSpec>> load_scenario(const std::string& path, const Suggest& suggest) {
  auto text = read_bounded_file(path, "scenario", kMaxScenarioFileBytes);
  if (!text) return text.error();
  return parse_scenario(*text, "scenario '" + path + "'", suggest);
}

}  // namespace hitl::faults
