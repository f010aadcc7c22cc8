// Error's kinds (base/common/expected.h): the default, the named constructors, context that keeps
// the kind, and the kind a bounded file read gives.
#include <gtest/gtest.h>

#include "base/common/bounded_read.h"
#include "base/common/expected.h"

namespace hitl {
namespace {

TEST(ErrorKind, AnErrorWithoutAKindIsAFailure) {
  const Error e{"no answer"};
  EXPECT_EQ(e.kind, ErrorKind::Failed);
  EXPECT_EQ(e.message, "no answer");
  const Status s = Error{"refused"};
  EXPECT_EQ(s.error().kind, ErrorKind::Failed);
}

TEST(ErrorKind, NamedConstructorsGiveTheirKind) {
  EXPECT_EQ(Error::usage("u").kind, ErrorKind::Usage);
  EXPECT_EQ(Error::input("i").kind, ErrorKind::Input);
  EXPECT_EQ(Error::unavailable("a").kind, ErrorKind::Unavailable);
  EXPECT_EQ(Error::failed("f").kind, ErrorKind::Failed);
  EXPECT_EQ(Error::input("i").message, "i");
}

TEST(ErrorKind, ContextKeepsTheKind) {
  const Error e = Error::unavailable("UDP port 14570 is already in use").prefixed("HIL link: ").suffixed(" (--clients 0?)");
  EXPECT_EQ(e.kind, ErrorKind::Unavailable);
  EXPECT_EQ(e.message, "HIL link: UDP port 14570 is already in use (--clients 0?)");
}

TEST(ErrorKind, WordsForJson) {
  EXPECT_STREQ(to_string(ErrorKind::Failed), "failed");
  EXPECT_STREQ(to_string(ErrorKind::Usage), "usage");
  EXPECT_STREQ(to_string(ErrorKind::Input), "input");
  EXPECT_STREQ(to_string(ErrorKind::Unavailable), "unavailable");
}

TEST(ErrorKind, AFileThatCannotBeReadIsInput) {
  auto missing = read_bounded_file("/nonexistent/hitl/trajectory.json", "trajectory", 1024);
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().kind, ErrorKind::Input);
  EXPECT_NE(missing.error().message.find("cannot read trajectory '/nonexistent/hitl/trajectory.json'"), std::string::npos);
  auto endless = read_bounded_file("/dev/zero", "trajectory", 1024);
  ASSERT_FALSE(endless);
  EXPECT_EQ(endless.error().kind, ErrorKind::Input);
}

}  // namespace
}  // namespace hitl
