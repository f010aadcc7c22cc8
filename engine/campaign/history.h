// The campaign history: every `hitl campaign run` stored in an SQLite database (Debian's libsqlite3):
// the campaign, the label the user names (a commit, a firmware version), the flight stack and its
// version (PX4's, when the flights flew PX4 SITL), when, the counts, each
// flight's outcome and each criterion's figure. `hitl campaign history` reads it back as per-
// criterion trends, and flags a regression: the latest run's figure worse than the runs before it
// by more than their spread.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "engine/campaign/campaign_file.h"
#include "engine/campaign/flight.h"
#include "engine/campaign/flight_run.h"

namespace hitl::campaign {

/// $XDG_DATA_HOME/hitl/campaigns.sqlite, or ~/.local/share/hitl/campaigns.sqlite; an Error when
/// neither XDG_DATA_HOME nor HOME is set.
Expected<std::string> default_history_path();

/// What one run stores besides its flights' results.
struct RunRecord {
  std::string label;        ///< --label (empty: none)
  std::string started_utc;  ///< "2026-11-29T11:30:00Z"
  double wall_s = 0;
  bool stopped = false;
};

/// Appends a run (making the file and its tables when new). An Error naming the file when it cannot
/// be opened or written (a file that is not a history database among them).
Status record_run(const std::string& history_path, const Campaign& campaign, const std::vector<Flight>& flights,
                  const std::vector<std::optional<FlightResult>>& results, const RunRecord& run);

/// One run's figure of one criterion, over the flights that measured it.
struct TrendPoint {
  int64_t run = 0;  ///< the run's number in the database
  std::string label;
  std::string started_utc;
  std::string stack_version;  ///< the flight stack's version in that run (PX4's: "v1.16.0"); "" for the emulated board
  std::size_t flights = 0;  ///< flights with a number for it
  std::size_t failed = 0;   ///< flights that broke it
  double mean = 0;
  double worst = 0;         ///< the largest for a "<=" criterion, the smallest for ">="
};

/// A criterion across the last runs, oldest first, and the verdict on the latest.
struct Trend {
  std::string criterion;
  std::string figure;
  std::string limit;  ///< as the latest run judged it: "<= 1.5"
  std::vector<TrendPoint> points;
  bool regression = false;
  std::string verdict;  ///< in words: why it is or is not a regression
};

struct History {
  std::string campaign;
  std::size_t runs = 0;  ///< in the database for this campaign
  std::vector<Trend> trends;
};

/// The names of the campaigns the database holds, most recent run first.
Expected<std::vector<std::string>> history_campaigns(const std::string& history_path);
/// The trends of `campaign` over its last `last_runs` runs (at least 2: the latest and one before).
Expected<History> read_history(const std::string& history_path, const std::string& campaign, std::size_t last_runs);

/// The regression rule on a trend's points (oldest first): with at least two runs before the
/// latest, the latest mean (the failed count for an "==" criterion) is worse than the earlier
/// runs' average by more than their spread (largest minus smallest); fills regression and verdict.
void judge_trend(Trend& trend);

}  // namespace hitl::campaign
