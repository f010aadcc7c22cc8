// AdaptiveBusyPoll: finds what is already waiting, backs off after spins that find nothing
// (doubling, up to kMaxBackoff) and fully after a wait that saw nothing, and spins again at once
// after one that found something. Counts, not times: nothing here asserts a speed.
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <unistd.h>

#include "engine/net/busy_poll.h"

namespace hitl::net {
namespace {

struct SocketPair {
  int fd[2] = {-1, -1};
  SocketPair() { EXPECT_EQ(::socketpair(AF_UNIX, SOCK_DGRAM, 0, fd), 0); }
  ~SocketPair() {
    ::close(fd[0]);
    ::close(fd[1]);
  }
  void send() { EXPECT_EQ(::write(fd[1], "x", 1), 1); }
  void drain() {
    char b[8];
    while (::recv(fd[0], b, sizeof b, MSG_DONTWAIT) > 0) {
    }
  }
};

TEST(AdaptiveBusyPoll, FindsWhatIsWaitingAndSpinsAgainAtOnce) {
  SocketPair s;
  AdaptiveBusyPoll poll;
  pollfd p{s.fd[0], POLLIN, 0};
  for (int i = 0; i < 5; ++i) {
    s.send();
    EXPECT_TRUE(poll.spin({&p, 1}));
    s.drain();
  }
  EXPECT_EQ(poll.spins_tried(), 5u);
  EXPECT_EQ(poll.spins_answered(), 5u);
  EXPECT_GE(poll.budget_s(), AdaptiveBusyPoll::kMinBudget_s);
  EXPECT_LE(poll.budget_s(), AdaptiveBusyPoll::kMaxBudget_s);
}

TEST(AdaptiveBusyPoll, BacksOffAfterSpinsThatFindNothing) {
  SocketPair s;
  AdaptiveBusyPoll poll;
  pollfd p{s.fd[0], POLLIN, 0};
  EXPECT_FALSE(poll.spin({&p, 1}));  // tried: nothing; skip 1
  EXPECT_FALSE(poll.spin({&p, 1}));  // skipped
  EXPECT_EQ(poll.spins_tried(), 1u);
  EXPECT_FALSE(poll.spin({&p, 1}));  // tried again: skip 2
  EXPECT_FALSE(poll.spin({&p, 1}));
  EXPECT_FALSE(poll.spin({&p, 1}));
  EXPECT_EQ(poll.spins_tried(), 2u);
  s.send();
  EXPECT_TRUE(poll.spin({&p, 1}));  // found: no more backing off
  EXPECT_TRUE(poll.spin({&p, 1}));  // still readable, tried at once
  EXPECT_EQ(poll.spins_tried(), 4u);
}

TEST(AdaptiveBusyPoll, AnIdlePeerCostsOneSpinInKMaxBackoffWaits) {
  SocketPair s;
  AdaptiveBusyPoll poll;
  pollfd p{s.fd[0], POLLIN, 0};
  poll.on_nothing();
  s.send();  // even with something waiting: no spin while backing off
  for (uint32_t i = 0; i < AdaptiveBusyPoll::kMaxBackoff; ++i) EXPECT_FALSE(poll.spin({&p, 1}));
  EXPECT_EQ(poll.spins_tried(), 0u);
  EXPECT_TRUE(poll.spin({&p, 1}));
}

}  // namespace
}  // namespace hitl::net
