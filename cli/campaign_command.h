// What other commands share with hitl campaign run: `hitl demo --campaign` runs a campaign file as
// `hitl campaign run FILE -j JOBS --out DIR --history FILE --label TEXT` does.
#pragma once

#include <cstddef>
#include <string>

#include "cli/common_options.h"

namespace hitl::cli {

struct CampaignFileRun {
  std::string file;
  std::size_t jobs = 0;  ///< 0: the cores
  std::string out_dir;
  std::string history;   ///< empty: the default history
  std::string label;
};

/// The run, its output and its exit code, as `hitl campaign run` gives them.
int run_campaign_file(const GlobalOptions& options, const CampaignFileRun& run);

}  // namespace hitl::cli
