// The pass criteria judged on a flight's summary: each named threshold holds or is broken, with the
// figure and its limit in words for the results (JUnit's failure message). A flight also fails when
// its trajectory was not flown to the end (the implicit criterion "flown").
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/campaign/campaign_file.h"

namespace hitl::campaign {

/// The implicit criterion every flight has: the session ended with its trajectory done.
inline constexpr const char* kFlownCriterion = "flown";

struct Verdict {
  std::string criterion;  ///< its name in the file, or kFlownCriterion
  std::string figure;     ///< the dotted path ("end" for flown)
  bool ok = false;
  nlohmann::json value;   ///< the figure's value (null when absent)
  std::string limit;      ///< "<= 1.5", ">= 200", "== false", "== trajectory_done"
  std::string message;    ///< "trajectory.rms_m = 2.31, limit <= 1.5" (empty when ok)
};

/// Every criterion of the campaign on `summary`, flown first, in the file's order.
std::vector<Verdict> judge(const Campaign& campaign, const nlohmann::json& summary);
/// All hold.
bool passed(const std::vector<Verdict>& verdicts);
nlohmann::json to_json(const Verdict& verdict);

}  // namespace hitl::campaign
