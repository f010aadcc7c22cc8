// A campaign's results folder, written after every run from the flights' result.json files:
// summary.json (every flight's outcome and why) and junit.xml (a testsuite per axis value the
// file names, a testcase per flight, a failure per broken criterion with the figure and its limit,
// the flight's summary line as its system-out), which GitLab, Jenkins and GitHub show as they are.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "base/common/expected.h"
#include "engine/campaign/campaign_file.h"
#include "engine/campaign/flight.h"
#include "engine/campaign/flight_run.h"

namespace hitl::campaign {

inline constexpr const char* kCampaignSummaryFile = "summary.json";
inline constexpr const char* kJunitFile = "junit.xml";

struct Tally {
  std::size_t flights = 0, passed = 0, failed = 0, errors = 0, missing = 0;
};
Tally tally(const std::vector<std::optional<FlightResult>>& results);

nlohmann::json campaign_summary_json(const Campaign& campaign, const std::vector<Flight>& flights,
                                     const std::vector<std::optional<FlightResult>>& results, double wall_s, bool stopped);
std::string junit_xml(const Campaign& campaign, const std::vector<Flight>& flights,
                      const std::vector<std::optional<FlightResult>>& results);
/// Both files into `out_dir`.
Status write_results(const std::string& out_dir, const Campaign& campaign, const std::vector<Flight>& flights,
                     const std::vector<std::optional<FlightResult>>& results, double wall_s, bool stopped);

}  // namespace hitl::campaign
