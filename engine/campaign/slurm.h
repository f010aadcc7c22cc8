// A campaign on Slurm (docs/campaigns.md "Slurm"): the flights as one job array, a task per flight
// (`hitl campaign run FILE --only $SLURM_ARRAY_TASK_ID --out DIR`) with the campaign's time limit,
// and `hitl campaign collect` as a job that depends on it (afterany). The batch scripts are written
// into the results folder and submitted with the cluster's own sbatch: hitl schedules nothing.
#pragma once

#include <cstddef>
#include <string>

#include "base/common/expected.h"
#include "engine/campaign/campaign_file.h"

namespace hitl::campaign {

struct SlurmOptions {
  std::string hitl;            ///< the hitl every node runs (absolute; on a shared file system)
  std::string campaign_path;   ///< the campaign file (absolute)
  std::string out_dir;         ///< the results folder (absolute; shared by every node)
  std::string partition;       ///< --partition (empty: the cluster's default)
  std::size_t max_running = 0; ///< at most this many tasks at once (the array's %N; 0: as Slurm schedules)
  std::string history;         ///< collect's --history (empty: --no-history)
  std::string label;           ///< collect's --label
};

/// "MM:SS" for --time: `seconds` rounded up to whole seconds.
std::string slurm_time(double seconds);

/// The job array's batch script for `flights` flights.
std::string slurm_flights_script(const Campaign& campaign, std::size_t flights, const SlurmOptions& options);
/// The collect job's batch script.
std::string slurm_collect_script(const Campaign& campaign, const SlurmOptions& options);

struct SlurmSubmission {
  std::string flights_job;  ///< the array's job id
  std::string collect_job;  ///< the collect job's id (runs after every task ended)
  std::string flights_script, collect_script;  ///< where the scripts were written
};

/// Writes both scripts into OUT/slurm/ and submits them with `sbatch` (a path): the array, then
/// collect with --dependency=afterany on it. An Error naming the command and its message when
/// sbatch refuses.
Expected<SlurmSubmission> submit_to_slurm(const Campaign& campaign, std::size_t flights, const SlurmOptions& options,
                                          const std::string& sbatch);

}  // namespace hitl::campaign
