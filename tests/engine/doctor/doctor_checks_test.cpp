// The doctor's check catalogue and summary (engine/doctor/check_catalog, check_result): the checks
// unique, grouped and in order, a fix only where one is needed, the worst verdict decides. Each
// check's decision on fixed inputs is tested beside this file, one file per engine/doctor/*_checks.
#include <gtest/gtest.h>

#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/doctor/check_catalog.h"
#include "engine/doctor/check_result.h"

namespace hitl::doctor {
namespace {

TEST(DoctorCatalog, ChecksAreUniqueGroupedAndInTheIssuesOrder) {
  const auto& checks = doctor_checks();
  ASSERT_EQ(checks.size(), 30u);
  std::set<std::string> ids;
  for (const auto& c : checks) EXPECT_TRUE(ids.insert(c.id).second) << c.id;
  const std::vector<std::string> groups = {group::kHost,     group::kLink,    group::kSensors, group::kParameters,
                                           group::kEstimator, group::kArming, group::kVio,     group::kSimulator, group::kPx4};
  std::size_t g = 0;
  for (const auto& c : checks) {
    while (g < groups.size() && groups[g] != c.group) ++g;
    ASSERT_LT(g, groups.size()) << c.id << " is out of group order";
  }
  EXPECT_THROW(check_info("no-such-check"), std::logic_error);
}

TEST(DoctorCatalog, FixOnlyForWarningsAndFailuresAndTheWorstDecides) {
  EXPECT_TRUE(make_result(check::kRoute, Verdict::Pass, "x", "do y").fix.empty());
  EXPECT_TRUE(make_result(check::kRoute, Verdict::Skip, "x", "do y").fix.empty());
  EXPECT_EQ(make_result(check::kRoute, Verdict::Fail, "x", "do y").fix, "do y");
  EXPECT_EQ(make_result(check::kRoute, Verdict::Fail, "x").group, "host");
  const auto s = summarize({make_result(check::kRoute, Verdict::Pass, ""), make_result(check::kAdb, Verdict::Skip, ""),
                            make_result(check::kPorts, Verdict::Warn, "")});
  EXPECT_TRUE(s.ok());
  EXPECT_EQ(s.worst, Verdict::Warn);
  const auto f = summarize({make_result(check::kRoute, Verdict::Fail, ""), make_result(check::kAdb, Verdict::Pass, "")});
  EXPECT_FALSE(f.ok());
  EXPECT_EQ(f.failed, 1u);
  EXPECT_STREQ(to_string(Verdict::Fail), "fail");
}

}  // namespace
}  // namespace hitl::doctor
