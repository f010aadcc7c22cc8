// A campaign's flights as other engines' units of work (engine/campaign/work_units.h): the GitHub
// Actions matrix and the Kubernetes Indexed Job, the latter against the fields the Kubernetes API
// requires of a batch/v1 Job (JobSpec.template; PodSpec.containers, each with a name; a Job's pods
// restart Never or OnFailure; completionMode Indexed needs completions, parallelism <= 10^5).
#include <gtest/gtest.h>

#include "engine/campaign/work_units.h"

namespace hitl::campaign {
namespace {

Campaign three_flights() {
  Campaign c;
  c.file = "c.toml";
  c.name = "Night_Regression.v2";
  c.time_limit_s = 120.5;
  c.trajectories = {{"hover", "hover.json", "/x/hover.json"}};
  FaultCase none;
  none.name = "none";
  c.fault_cases = {none};
  c.seeds = {1, 2, 3};
  c.speeds = {0};
  return c;
}

TEST(CampaignWorkUnits, TheCiMatrixHasAJobPerFlight) {
  const Campaign c = three_flights();
  const auto flights = expand(c);
  auto m = ci_matrix(c, flights);
  ASSERT_TRUE(m) << m.error().message;
  ASSERT_EQ((*m)["include"].size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ((*m)["include"][i]["index"], i);
    EXPECT_EQ((*m)["include"][i]["id"], flights[i].id);
    EXPECT_EQ((*m)["include"][i]["name"], flights[i].name);
  }
  Campaign big = c;
  big.seeds.clear();
  for (uint64_t s = 1; s <= kMaxCiMatrixJobs + 1; ++s) big.seeds.push_back(s);
  auto refused = ci_matrix(big, expand(big));
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("at most 256 jobs"), std::string::npos) << refused.error().message;
}

TEST(CampaignWorkUnits, TheIndexedJobHasWhatTheJobApiRequires) {
  const Campaign c = three_flights();
  IndexedJobOptions o;
  o.image = "registry.example/hitl:1.0";
  o.campaign_path = "/campaigns/night's.toml";
  o.results_claim = "results";
  o.parallelism = 2;
  const auto job = k8s_indexed_job(c, 3, o);
  EXPECT_EQ(job["apiVersion"], "batch/v1");
  EXPECT_EQ(job["kind"], "Job");
  EXPECT_EQ(job["metadata"]["name"], "hitl-campaign-night-regression-v2");  // DNS-1123
  const auto& spec = job["spec"];
  EXPECT_EQ(spec["completionMode"], "Indexed");
  EXPECT_EQ(spec["completions"], 3);
  EXPECT_EQ(spec["parallelism"], 2);
  ASSERT_TRUE(spec.contains("template"));
  const auto& pod = spec["template"]["spec"];
  EXPECT_TRUE(pod["restartPolicy"] == "Never" || pod["restartPolicy"] == "OnFailure");
  EXPECT_EQ(pod["activeDeadlineSeconds"], 121);  // whole seconds, rounded up
  ASSERT_EQ(pod["containers"].size(), 1u);
  const auto& container = pod["containers"][0];
  EXPECT_FALSE(container["name"].get<std::string>().empty());
  EXPECT_EQ(container["image"], o.image);
  const std::string script = container["command"][2];
  EXPECT_NE(script.find("hitl campaign run '/campaigns/night'\\''s.toml' --only \"$JOB_COMPLETION_INDEX\""), std::string::npos)
      << script;
  EXPECT_NE(script.find("--out /results/'hitl-campaign-night-regression-v2'"), std::string::npos) << script;
  EXPECT_EQ(pod["volumes"][0]["persistentVolumeClaim"]["claimName"], "results");
  EXPECT_EQ(container["volumeMounts"][0]["mountPath"], "/results");
  o.parallelism = 0;
  EXPECT_EQ(k8s_indexed_job(c, 3, o)["spec"]["parallelism"], 3);  // every flight at once
  EXPECT_EQ(k8s_job_name(std::string(100, 'a')).size(), 63u);
}

}  // namespace
}  // namespace hitl::campaign
