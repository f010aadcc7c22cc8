// hitl campaign history, and where a run's history goes (--history, --no-history): the
// campaign's SQLite history (engine/campaign/history.h) read back as trends per criterion.
#pragma once

#include <cstddef>
#include <string>

#include "base/common/expected.h"
#include "cli/common_options.h"

namespace hitl::cli {

/// hitl campaign history's options.
struct CampaignHistoryOptions {
  std::string campaign;  ///< empty: the campaign of the latest run
  std::string history;
  std::size_t last_runs = 10;
};

/// --history FILE, or the default under the user's data folder; the error names the option.
Expected<std::string> history_path(const std::string& given);
/// The history a run goes into: none with --no-history (empty), else as history_path().
Expected<std::string> run_history(bool no_history, const std::string& given);
/// hitl campaign history: the trends of a campaign's last runs; exit 1 when one regressed.
int run_history_command(const GlobalOptions& g, const CampaignHistoryOptions& o);

}  // namespace hitl::cli
