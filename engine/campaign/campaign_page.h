// A campaign's page (DIR/index.html, docs/campaigns.md "The page"): one self-contained HTML file that
// opens offline. Its header (the campaign, the run, the counts); the matrix as a table, a row per
// trajectory and a column per fault case, each cell listing its flights (a seed, and a speed when the
// file names speeds) coloured by outcome with the broken criteria as text, each flight a link to its
// report.html (else its summary.json, else its log.txt); each criterion's figure across the seeds of
// each cell (min, median, max: a table, and for a number figure a plot drawn by dygraphs as the
// report inlines it); and, with a history, each criterion's trend over the campaign's last runs with
// the regressions `hitl campaign history` flags. Without Debian's dygraphs the tables stay and the
// page says the plots are missing. Its size grows linearly with the flights and the runs shown.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "engine/campaign/campaign_file.h"
#include "engine/campaign/flight.h"
#include "engine/campaign/flight_run.h"
#include "engine/campaign/history.h"
#include "engine/report/dygraphs.h"

namespace hitl::campaign {

inline constexpr const char* kPageFile = "index.html";
/// The runs of the history the page draws (as `hitl campaign history`'s default --last).
inline constexpr std::size_t kPageTrendRuns = 10;
/// Text the page carries per flight (a broken criterion's message, a reason) is cut to this many bytes.
inline constexpr std::size_t kPageMaxTextBytes = 400;

/// What the page says about this run besides the flights' results.
struct PageRun {
  std::string label;        ///< --label (empty: none)
  std::string started_utc;  ///< "2026-11-29T11:30:00Z"
  std::string hitl_version;
  double wall_s = 0;
  bool stopped = false;
  bool collected = false;   ///< written by `hitl campaign collect` (wall_s: the flights' own times added up)
  std::string no_history_reason = "this run was kept out of the history (--no-history)";  ///< without a history path
};

/// Everything one page shows.
struct PageInput {
  const Campaign* campaign = nullptr;
  const std::vector<Flight>* flights = nullptr;
  const std::vector<std::optional<FlightResult>>* results = nullptr;  ///< by flight index
  /// Each flight's link, relative to the page ("flights/<id>/report.html"), by index; "": none.
  std::vector<std::string> links;
  PageRun run;
  std::optional<History> history;  ///< none: no history in use
  std::string history_note;        ///< why there are no trends ("--no-history", the database's error)
  const report::DygraphsLibrary* dygraphs = nullptr;  ///< none: tables only
  std::string dygraphs_note;       ///< why there are no plots
};

/// The page's HTML.
std::string campaign_page_html(const PageInput& input);

/// The link of a flight's folder `folder` as the page shows it (`relative` its path from the page):
/// its report.html, else its summary.json, else its log.txt, else "" (not flown).
std::string flight_link(const std::string& folder, const std::string& relative);

/// Writes DIR/index.html for these results: the links from the flights' folders, the trends from
/// `history_path` (empty: none in use, the page says run.no_history_reason) over kPageTrendRuns runs, dygraphs from Debian's package (when
/// it is missing the page has its tables only). An Error when the page cannot be written.
Status write_campaign_page(const std::string& out_dir, const Campaign& campaign, const std::vector<Flight>& flights,
                           const std::vector<std::optional<FlightResult>>& results, const PageRun& run,
                           const std::string& history_path);

}  // namespace hitl::campaign
