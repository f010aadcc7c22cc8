#include "engine/campaign/criteria.h"

#include <cstdio>
#include <optional>
#include <regex>

#include "engine/campaign/flight_summary.h"

namespace hitl::campaign {

namespace {

std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

std::string value_text(const nlohmann::json& v) {
  if (v.is_null()) return "absent";
  if (v.is_number()) return number_text(v.get<double>());
  if (v.is_string()) return v.get<std::string>();
  return v.dump();
}

Verdict judge_one(const Criterion& c, const nlohmann::json& summary) {
  Verdict v;
  v.criterion = c.name;
  v.figure = c.figure;
  const auto* found = figure_at(summary, c.figure);
  v.value = found != nullptr ? *found : nlohmann::json(nullptr);
  switch (c.comparison) {
    case Comparison::AtMost:
      v.limit = "<= " + number_text(c.limit);
      v.ok = v.value.is_number() && v.value.get<double>() <= c.limit;
      break;
    case Comparison::AtLeast:
      v.limit = ">= " + number_text(c.limit);
      v.ok = v.value.is_number() && v.value.get<double>() >= c.limit;
      break;
    case Comparison::Equals:
      if (c.equals_text) {
        v.limit = "== " + *c.equals_text;
        v.ok = v.value.is_string() && v.value.get<std::string>() == *c.equals_text;
      } else if (c.equals_bool) {
        v.limit = std::string("== ") + (*c.equals_bool ? "true" : "false");
        v.ok = v.value.is_boolean() && v.value.get<bool>() == *c.equals_bool;
      } else {
        v.limit = "== " + number_text(c.limit);
        v.ok = v.value.is_number() && v.value.get<double>() == c.limit;
      }
      break;
  }
  if (!v.ok) v.message = c.figure + " = " + value_text(v.value) + ", limit " + v.limit;
  return v;
}

/// The first start of fault `name` in the summary's "faults" records, or nullopt.
std::optional<double> fault_start_s(const nlohmann::json& summary, const std::string& name) {
  const auto* records = figure_at(summary, "faults");
  if (records == nullptr || !records->is_array()) return std::nullopt;
  std::optional<double> first;
  for (const auto& r : *records)
    if (r.is_object() && r.value("name", std::string()) == name && r.contains("start_s") && r["start_s"].is_number()) {
      const double t = r["start_s"].get<double>();
      if (!first || t < *first) first = t;
    }
  return first;
}

bool from_flight_stack(const std::string& source) { return source != "simulator" && source != "pilot"; }

bool matches(const Expectation& e, const std::string& source, const std::string& text) {
  switch (e.kind) {
    case ExpectKind::Statustext: {
      if (!from_flight_stack(source) || text == "armed" || text == "disarmed" || text.rfind("mode ", 0) == 0) return false;
      return std::regex_search(text, std::regex(e.pattern, std::regex::ECMAScript));
    }
    case ExpectKind::Mode: return from_flight_stack(source) && text == "mode " + e.pattern;
    case ExpectKind::Event: return std::regex_search(text, std::regex(e.pattern, std::regex::ECMAScript));
  }
  return false;
}

/// An expectation on the flight's events; nullopt when it does not apply (the flight has no such fault).
std::optional<Verdict> judge_expectation(const Expectation& e, const nlohmann::json& summary) {
  Verdict v;
  v.criterion = e.name;
  v.figure = "events";
  const std::string what = e.kind == ExpectKind::Mode ? "mode " + e.pattern : std::string(to_string(e.kind)) + " ~ /" + e.pattern + "/";
  double from_s = 0;
  std::string after = "the flight's start";
  if (!e.after_fault.empty()) {
    const auto start = fault_start_s(summary, e.after_fault);
    if (!start) {
      const auto* specs = figure_at(summary, "flight.faults");
      bool planned = false;
      if (specs != nullptr && specs->is_array())
        for (const auto& spec : *specs)
          if (spec.is_string() && spec.get<std::string>().rfind(e.after_fault, 0) == 0) planned = true;
      if (!planned) return std::nullopt;  // not this flight's fault: nothing to judge
      v.limit = what + " after " + e.after_fault;
      v.value = nullptr;
      v.message = "the fault " + e.after_fault + " never started, so " + what + " could not follow it";
      return v;
    }
    from_s = *start;
    char text[64];
    std::snprintf(text, sizeof text, "%s's start at %.3f s", e.after_fault.c_str(), from_s);
    after = text;
  }
  v.limit = what + (e.within_s ? " within " + number_text(*e.within_s) + " s of " : " after ") + after;
  const auto* events = figure_at(summary, "events");
  if (events != nullptr && events->is_array())
    for (const auto& ev : *events) {
      if (!ev.is_object() || !ev.contains("t_s") || !ev["t_s"].is_number()) continue;
      const double t = ev["t_s"].get<double>();
      if (t < from_s || (e.within_s && t > from_s + *e.within_s)) continue;
      if (!matches(e, ev.value("source", std::string()), ev.value("text", std::string()))) continue;
      v.ok = true;
      v.value = ev;
      return v;
    }
  v.value = nullptr;
  v.message = "no " + what + (e.within_s ? " within " + number_text(*e.within_s) + " s of " : " after ") + after;
  return v;
}

}  // namespace

std::vector<Verdict> judge(const Campaign& campaign, const nlohmann::json& summary) {
  std::vector<Verdict> out;
  Verdict flown;
  flown.criterion = kFlownCriterion;
  flown.figure = "end";
  flown.value = summary.contains("end") ? summary["end"] : nlohmann::json(nullptr);
  flown.limit = "== trajectory_done";
  flown.ok = flown.value == "trajectory_done";
  if (!flown.ok) {
    flown.message = "end = " + value_text(flown.value) + ", limit " + flown.limit;
    const auto* failure = figure_at(summary, "trajectory.failure");
    if (failure != nullptr && failure->is_string() && !failure->get<std::string>().empty())
      flown.message += " (" + failure->get<std::string>() + ")";
  }
  out.push_back(std::move(flown));
  for (const auto& c : campaign.criteria) out.push_back(judge_one(c, summary));
  for (const auto& e : campaign.expectations)
    if (auto v = judge_expectation(e, summary)) out.push_back(std::move(*v));
  return out;
}

bool passed(const std::vector<Verdict>& verdicts) {
  for (const auto& v : verdicts)
    if (!v.ok) return false;
  return true;
}

nlohmann::json to_json(const Verdict& v) {
  return {{"criterion", v.criterion}, {"figure", v.figure}, {"ok", v.ok}, {"value", v.value}, {"limit", v.limit},
          {"message", v.message}};
}

}  // namespace hitl::campaign
