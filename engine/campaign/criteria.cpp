#include "engine/campaign/criteria.h"

#include <cstdio>

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
      if (c.equals_bool) {
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
