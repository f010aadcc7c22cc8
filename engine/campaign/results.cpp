// The JUnit XML is written with pugixml (Debian's libpugixml, already the dialect reader's): its
// escaping of names, messages and summary lines is not ours to get wrong.
#include "engine/campaign/results.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include <pugixml.hpp>

namespace hitl::campaign {

namespace {

std::string seconds_text(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", s);
  return text;
}

std::string number_text(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

double flight_time_s(const FlightResult& r) { return r.process_wall_s > 0 ? r.process_wall_s : r.wall_s; }

/// The axes the file names, each value with the flights that have it.
struct AxisValue {
  std::string suite;  ///< "trajectory=square"
  std::function<bool(const Flight&)> has;
};

std::vector<AxisValue> axis_values(const Campaign& c) {
  std::vector<AxisValue> out;
  for (const auto& t : c.trajectories) {
    const std::string name = t.name;
    out.push_back({"trajectory=" + name, [name](const Flight& f) { return f.trajectory->name == name; }});
  }
  for (const auto& fc : c.fault_cases) {
    const std::string name = fc.name;
    out.push_back({"faults=" + name, [name](const Flight& f) { return f.fault_case->name == name; }});
  }
  for (const auto seed : c.seeds)
    out.push_back({"seed=" + std::to_string(seed), [seed](const Flight& f) { return f.seed == seed; }});
  if (c.speeds.size() > 1 || c.speeds.front() != 0)
    for (const double speed : c.speeds)
      out.push_back({"speed=" + number_text(speed), [speed](const Flight& f) { return f.speed == speed; }});
  return out;
}

void add_testcase(pugi::xml_node suite, const Campaign& c, const std::string& suite_name, const Flight& f,
                  const std::optional<FlightResult>& r) {
  auto tc = suite.append_child("testcase");
  tc.append_attribute("name") = f.name.c_str();
  tc.append_attribute("classname") = (c.name + "." + suite_name).c_str();
  tc.append_attribute("time") = seconds_text(r ? flight_time_s(*r) : 0.0).c_str();
  tc.append_attribute("id") = f.id.c_str();
  if (!r) {
    tc.append_child("skipped").append_attribute("message") = "not flown (the campaign was stopped before it; --resume flies it)";
    return;
  }
  if (r->outcome == "error") {
    auto e = tc.append_child("error");
    e.append_attribute("message") = r->reason.c_str();
    e.append_attribute("type") = "error";
  }
  for (const auto& v : r->verdicts) {
    if (v.ok) continue;
    auto e = tc.append_child("failure");
    e.append_attribute("message") = (v.criterion + ": " + v.message).c_str();
    e.append_attribute("type") = v.criterion.c_str();
    e.text() = ("criterion " + v.criterion + ": figure " + v.figure + " is " + (v.value.is_null() ? "absent" : v.value.dump()) +
                ", limit " + v.limit).c_str();
  }
  tc.append_child("system-out").text() = r->summary_line.c_str();
}

}  // namespace

Tally tally(const std::vector<std::optional<FlightResult>>& results) {
  Tally t;
  t.flights = results.size();
  for (const auto& r : results) {
    if (!r) ++t.missing;
    else if (r->outcome == "passed") ++t.passed;
    else if (r->outcome == "failed") ++t.failed;
    else ++t.errors;
  }
  return t;
}

nlohmann::json campaign_summary_json(const Campaign& c, const std::vector<Flight>& flights,
                                     const std::vector<std::optional<FlightResult>>& results, double wall_s, bool stopped) {
  const Tally t = tally(results);
  nlohmann::json list = nlohmann::json::array();
  for (const auto& f : flights) {
    const auto& r = results[f.index];
    nlohmann::json failures = nlohmann::json::array();
    if (r)
      for (const auto& v : r->verdicts)
        if (!v.ok) failures.push_back({{"criterion", v.criterion}, {"figure", v.figure}, {"value", v.value}, {"limit", v.limit}});
    list.push_back({{"index", f.index},
                    {"id", f.id},
                    {"name", f.name},
                    {"trajectory", f.trajectory->as_written},
                    {"fault_case", f.fault_case->name},
                    {"seed", f.seed},
                    {"speed", f.speed},
                    {"outcome", r ? r->outcome : "missing"},
                    {"reason", r ? r->reason : ""},
                    {"failures", failures},
                    {"summary_line", r ? r->summary_line : ""},
                    {"wall_s", r ? flight_time_s(*r) : 0.0},
                    {"folder", "flights/" + f.id}});
  }
  return {{"type", "summary"},   {"campaign", c.name},   {"file", c.file},     {"stack", to_string(c.stack)}, {"stack_version", stack_version(c)},
          {"flights", t.flights}, {"passed", t.passed},   {"failed", t.failed}, {"errors", t.errors},
          {"missing", t.missing}, {"ok", t.passed == t.flights},                {"stopped", stopped},
          {"wall_s", wall_s},     {"results", list}};
}

std::string junit_xml(const Campaign& c, const std::vector<Flight>& flights, const std::vector<std::optional<FlightResult>>& results) {
  pugi::xml_document doc;
  auto decl = doc.append_child(pugi::node_declaration);
  decl.append_attribute("version") = "1.0";
  decl.append_attribute("encoding") = "UTF-8";
  auto root = doc.append_child("testsuites");
  root.append_attribute("name") = c.name.c_str();
  std::size_t all_tests = 0, all_failures = 0, all_errors = 0, all_skipped = 0;
  double all_time = 0;
  for (const auto& axis : axis_values(c)) {
    auto suite = root.append_child("testsuite");
    suite.append_attribute("name") = axis.suite.c_str();
    auto properties = suite.append_child("properties");  // the flight stack, which no axis names
    auto stack = properties.append_child("property");
    stack.append_attribute("name") = "stack";
    stack.append_attribute("value") = to_string(c.stack);
    if (const std::string version = stack_version(c); !version.empty()) {
      auto v = properties.append_child("property");
      v.append_attribute("name") = "stack_version";
      v.append_attribute("value") = version.c_str();
    }
    std::size_t tests = 0, failures = 0, errors = 0, skipped = 0;
    double time = 0;
    for (const auto& f : flights) {
      if (!axis.has(f)) continue;
      const auto& r = results[f.index];
      ++tests;
      if (!r) ++skipped;
      else if (r->outcome == "error") ++errors;
      else if (r->outcome == "failed") ++failures;
      if (r) time += flight_time_s(*r);
      add_testcase(suite, c, axis.suite, f, r);
    }
    suite.append_attribute("tests") = tests;
    suite.append_attribute("failures") = failures;
    suite.append_attribute("errors") = errors;
    suite.append_attribute("skipped") = skipped;
    suite.append_attribute("time") = seconds_text(time).c_str();
    all_tests += tests;
    all_failures += failures;
    all_errors += errors;
    all_skipped += skipped;
    all_time += time;
  }
  root.append_attribute("tests") = all_tests;
  root.append_attribute("failures") = all_failures;
  root.append_attribute("errors") = all_errors;
  root.append_attribute("skipped") = all_skipped;
  root.append_attribute("time") = seconds_text(all_time).c_str();
  std::ostringstream out;
  doc.save(out, "  ");
  return out.str();
}

Status write_results(const std::string& out_dir, const Campaign& c, const std::vector<Flight>& flights,
                     const std::vector<std::optional<FlightResult>>& results, double wall_s, bool stopped) {
  auto write = [&](const char* name, const std::string& text) -> Status {
    const auto path = std::filesystem::path(out_dir) / name;
    std::ofstream out(path, std::ios::trunc);
    out << text;
    if (!out) return Error::unavailable("cannot write " + path.string());
    return Ok{};
  };
  if (auto ok = write(kCampaignSummaryFile, campaign_summary_json(c, flights, results, wall_s, stopped).dump(2) + "\n"); !ok) return ok;
  return write(kJunitFile, junit_xml(c, flights, results));
}

}  // namespace hitl::campaign
