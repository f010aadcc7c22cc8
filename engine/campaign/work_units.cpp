#include "engine/campaign/work_units.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "base/common/shell_quote.h"

namespace hitl::campaign {

Expected<nlohmann::json> ci_matrix(const Campaign& campaign, const std::vector<Flight>& flights) {
  if (flights.size() > kMaxCiMatrixJobs)
    return Error::input(campaign.file + ": " + std::to_string(flights.size()) + " flights; a GitHub Actions matrix runs at most " +
                        std::to_string(kMaxCiMatrixJobs) + " jobs (split the campaign, or use hitl campaign k8s)");
  nlohmann::json include = nlohmann::json::array();
  for (const Flight& f : flights) include.push_back({{"index", f.index}, {"id", f.id}, {"name", f.name}});
  return nlohmann::json{{"include", include}};
}

std::string k8s_job_name(const std::string& campaign_name) {
  std::string name = "hitl-campaign-";
  for (char c : campaign_name) {
    const unsigned char u = static_cast<unsigned char>(c);
    name += std::isalnum(u) ? static_cast<char>(std::tolower(u)) : '-';
  }
  if (name.size() > 63) name.resize(63);
  while (!name.empty() && name.back() == '-') name.pop_back();
  return name;
}

nlohmann::json k8s_indexed_job(const Campaign& campaign, std::size_t flights, const IndexedJobOptions& options) {
  const std::string name = k8s_job_name(campaign.name);
  const nlohmann::json labels = {{"app.kubernetes.io/name", "hitl"}, {"hitl/campaign", name.substr(std::string("hitl-campaign-").size())}};
  // Exit 1 is a flight that failed its criteria: a result like any other, not a pod to retry.
  const std::string script = "hitl campaign run " + shell_quoted(options.campaign_path) +
                             " --only \"$JOB_COMPLETION_INDEX\" --out /results/" + shell_quoted(name) +
                             "; rc=$?; [ \"$rc\" -le 1 ]";
  nlohmann::json container = {{"name", "flight"},
                              {"image", options.image},
                              {"command", {"sh", "-c", script}},
                              {"volumeMounts", {{{"name", "results"}, {"mountPath", "/results"}}}}};
  nlohmann::json pod_spec = {{"restartPolicy", "Never"},
                             {"activeDeadlineSeconds", static_cast<long long>(std::ceil(campaign.time_limit_s))},
                             {"containers", {container}},
                             {"volumes", {{{"name", "results"}, {"persistentVolumeClaim", {{"claimName", options.results_claim}}}}}}};
  const std::size_t parallelism = options.parallelism == 0 ? flights : std::min(options.parallelism, flights);
  return {{"apiVersion", "batch/v1"},
          {"kind", "Job"},
          {"metadata", {{"name", name}, {"labels", labels}}},
          {"spec",
           {{"completionMode", "Indexed"},
            {"completions", flights},
            {"parallelism", parallelism},
            {"backoffLimit", flights},
            {"template", {{"metadata", {{"labels", labels}}}, {"spec", pod_spec}}}}}};
}

}  // namespace hitl::campaign
