// A campaign's flights as units of work for an engine that is not hitl's (docs/campaigns.md "Past
// one machine"): each flight is `hitl campaign run FILE --only INDEX --out DIR`, and these describe
// the set in the form each engine takes. The matrix GitHub Actions' strategy takes, and a
// Kubernetes Indexed Job (batch/v1, completionMode Indexed: the flight from JOB_COMPLETION_INDEX),
// as JSON, which kubectl takes as it takes YAML.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "base/common/expected.h"
#include "engine/campaign/campaign_file.h"
#include "engine/campaign/flight.h"

namespace hitl::campaign {

/// GitHub Actions runs at most 256 jobs from one matrix.
inline constexpr std::size_t kMaxCiMatrixJobs = 256;

/// {"include": [{"index": 0, "id": "...", "name": "square/none/seed-1"}, ...]}: a job per flight,
/// for `strategy.matrix: ${{ fromJSON(...) }}`; refused beyond kMaxCiMatrixJobs flights.
Expected<nlohmann::json> ci_matrix(const Campaign& campaign, const std::vector<Flight>& flights);

struct IndexedJobOptions {
  std::string image;          ///< the container image with hitl and the campaign's files
  std::string campaign_path;  ///< the campaign file inside the image
  std::string results_claim;  ///< the PersistentVolumeClaim every flight writes its results to (/results)
  std::size_t parallelism = 0;  ///< pods at a time (0: every flight at once, as the cluster allows)
};

/// "hitl-campaign-NAME", as a DNS-1123 name (lower case, digits and '-', at most 63 characters).
std::string k8s_job_name(const std::string& campaign_name);

/// The Indexed Job: one completion per flight, each pod `hitl campaign run PATH --only
/// $JOB_COMPLETION_INDEX --out /results/` on the claim, killed past the campaign's time_limit_s
/// (activeDeadlineSeconds); a flight that failed its criteria still completes (its result says
/// so), a crash fails its pod.
nlohmann::json k8s_indexed_job(const Campaign& campaign, std::size_t flights, const IndexedJobOptions& options);

}  // namespace hitl::campaign
