#include "engine/faults/scenario.h"

#include <optional>

#include <nlohmann/json.hpp>

#include "base/common/bounded_read.h"

namespace hitl::faults {
namespace {

using nlohmann::json;

Expected<double> number_field(const json& event, const char* key, const std::string& where) {
  const json& v = event.at(key);
  if (!v.is_number()) return Error{where + "." + key + ": must be a number (got " + v.dump() + ")"};
  return v.get<double>();
}

Expected<std::vector<double>> args_field(const json& v, const std::string& where) {
  std::vector<double> args;
  if (v.is_array()) {
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (!v[i].is_number()) return Error{where + ".args[" + std::to_string(i) + "]: must be a number (got " + v[i].dump() + ")"};
      args.push_back(v[i].get<double>());
    }
    return args;
  }
  if (!v.is_string()) return Error{where + ".args: must be an array of numbers or a string \"2,0.6\" (got " + v.dump() + ")"};
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

Expected<FaultSpec> parse_event(const json& event, const std::string& where, const Suggest& suggest) {
  if (!event.is_object()) return Error{where + ": must be an object {\"at_s\", \"fault\", ...} (got " + event.dump() + ")"};
  for (const auto& [key, value] : event.items())
    if (key != "at_s" && key != "fault" && key != "args" && key != "duration_s")
      return Error{where + ": unknown key '" + key + "' (an event has at_s, fault, args, duration_s)"};
  if (!event.contains("fault")) return Error{where + ": no \"fault\""};
  if (!event.contains("at_s")) return Error{where + ": no \"at_s\" (the start, simulated seconds)"};
  if (!event.at("fault").is_string()) return Error{where + ".fault: must be a fault's name (got " + event.at("fault").dump() + ")"};
  const std::string name = event.at("fault").get<std::string>();
  auto at = number_field(event, "at_s", where);
  if (!at) return at.error();
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
  if (!spec) return Error{where + ": " + spec.error().message};
  return spec;
}

}  // namespace

Expected<std::vector<FaultSpec>> parse_scenario(const std::string& text, const std::string& where, const Suggest& suggest) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    return Error{where + ": not JSON: " + e.what()};
  }
  if (!doc.is_object() || !doc.contains("events"))
    return Error{where + ": must be an object {\"events\": [...]} (docs/faults.md \"Scenario files\")"};
  for (const auto& [key, value] : doc.items())
    if (key != "events" && key != "description")
      return Error{where + ": unknown key '" + key + "' (a scenario has events and description)"};
  if (doc.contains("description") && !doc.at("description").is_string())
    return Error{where + ".description: must be a string"};
  const json& events = doc.at("events");
  if (!events.is_array()) return Error{where + ".events: must be an array of events"};
  if (events.size() > kMaxScenarioEvents)
    return Error{where + ".events: more than " + std::to_string(kMaxScenarioEvents) + " events"};
  std::vector<FaultSpec> specs;
  for (std::size_t i = 0; i < events.size(); ++i) {
    auto spec = parse_event(events[i], where + ": events[" + std::to_string(i) + "]", suggest);
    if (!spec) return spec.error();
    specs.push_back(std::move(spec.value()));
  }
  return specs;
}

Expected<std::vector<FaultSpec>> load_scenario(const std::string& path, const Suggest& suggest) {
  auto text = read_bounded_file(path, "scenario", kMaxScenarioFileBytes);
  if (!text) return text.error();
  return parse_scenario(*text, "scenario '" + path + "'", suggest);
}

}  // namespace hitl::faults
