// hitl sim end to end, --lockstep: the session steps only on the board's answers, falls back when
// they stop, never advances early on a late second answer, and ends on time against a dead board
// then gives up.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <deque>
#include <thread>

#include "tests/cli/sim_board.h"

namespace hitl {
namespace {

using namespace sim_e2e;

TEST(SimE2E, LockstepStepsOnlyOnAnswersAndFallsBackWhenTheyStop) {
  Board board;
  board.serve([](const msg::HilSensor&, uint64_t i) -> std::optional<msg::HilActuatorControls> {
    if (i >= 300) return std::nullopt;  // stops answering after 300 steps
    return actuators(0.0, true);
  });
  Process sim(board.sim_args({"--duration", "1.6", "--speed", "0", "--lockstep", "--lockstep-timeout", "0.02", "--no-vio"}));
  EXPECT_EQ(sim.wait(60s), 0) << sim.err();
  const auto j = last_json(sim.out());
  // Each of the board's 300 answers, less those to the free run before its first one, ended a wait.
  EXPECT_GE(j["lockstep"]["waits"].get<int>(), 50);
  // One wait runs out; then the session steps on without waiting until the board is heard again.
  EXPECT_EQ(j["lockstep"]["fallbacks"].get<int>(), 1);
  EXPECT_NE(sim.err().find("lockstep: no HIL_ACTUATOR_CONTROLS"), std::string::npos) << sim.err();
  EXPECT_NE(sim.err().find("stepping on without waiting"), std::string::npos) << sim.err();
}

/// Answers HIL_SENSORs in lockstep, stamping each answer with the HIL_SENSOR's time_usec as PX4
/// SITL does, but first repeats its answer to the previous one (late) and answers only 3 ms later.
/// Counts the HIL_SENSORs that arrived before it answered: the simulator stepped on without the
/// answer (on the late repeat).
struct DoubleAnsweringBoard {
  uint64_t answered = 0, early = 0;
  void run(Board& board, const std::atomic<bool>& stop) {
    auto set = mavlink::MessageSet::compiled();
    mavlink::FrameParser parser(set);
    std::deque<uint64_t> pending;
    auto drain = [&] {
      bool newer = false;
      while (auto d = board.peer().endpoint().receive())
        parser.parse_datagram(d->bytes, [&](const mavlink::Frame& f) {
          if (!f.is<msg::HilSensor>()) return;
          pending.push_back(f.as<msg::HilSensor>().time_usec);
          newer = true;
        });
      return newer;
    };
    uint64_t previous = 0;
    const auto until = std::chrono::steady_clock::now() + 60s;
    while (!stop.load() && std::chrono::steady_clock::now() < until) {
      if (pending.empty()) {
        if (board.peer().endpoint().wait_readable(20)) drain();
        continue;
      }
      const uint64_t t = pending.back();  // a backlog (the free run before the first answer): the newest only
      pending.clear();
      if (previous != 0) {
        auto late = actuators(0.0, true);
        late.time_usec = previous;
        board.peer().send(late);
      }
      std::this_thread::sleep_for(3ms);
      // A newer HIL_SENSOR here before the answer went out: the simulator stepped without it (on
      // the late repeat). (The first answers end the free run it makes until it hears the board.)
      if (drain() && answered > 10) ++early;
      auto a = actuators(0.0, true);
      a.time_usec = t;
      board.peer().send(a);
      ++answered;
      previous = t;
    }
  }
};

TEST(SimE2E, LateSecondAnswersNeverAdvanceLockstepEarly) {
  Board board;
  DoubleAnsweringBoard scripted;
  std::atomic<bool> stop{false};
  std::thread player([&] { scripted.run(board, stop); });
  Process sim(board.sim_args({"--duration", "3", "--speed", "0", "--lockstep", "--no-vio"}));
  EXPECT_EQ(sim.wait(60s), 0) << sim.err();
  stop = true;
  player.join();
  const auto j = last_json(sim.out());
  EXPECT_GE(scripted.answered, 100u);
  // A HIL_SENSOR already waiting when the board answers went out before the answer: stepped early.
  EXPECT_LE(scripted.early, scripted.answered / 50) << scripted.early << " of " << scripted.answered;
  EXPECT_GE(j["lockstep"]["late_answers"].get<uint64_t>() + 10, scripted.answered);
  EXPECT_EQ(j["lockstep"]["fallbacks"], 0);
  EXPECT_EQ(j["lockstep"]["foreign_clock"], 0);
}

TEST(SimE2E, LockstepAgainstADeadBoardEndsOnTimeThenGivesUp) {
  Board board;
  board.serve([](const msg::HilSensor&, uint64_t i) -> std::optional<msg::HilActuatorControls> {
    if (i >= 50) return std::nullopt;  // the board dies
    return actuators(0.0, false);
  });
  // --duration bounds the wall time: one wait runs out, then the session steps on in real time.
  const auto start = std::chrono::steady_clock::now();
  Process sim(board.sim_args({"--duration", "4", "--lockstep", "--no-vio"}));
  EXPECT_EQ(sim.wait(60s), 0) << sim.err();
  EXPECT_LT(std::chrono::steady_clock::now() - start, 20s);
  EXPECT_EQ(last_json(sim.out())["end"], "duration");
  board.stop();

  // Longer than the give-up time (10 s of silence): the session ends, says what to restart, exit 1.
  Board dead;
  dead.serve([](const msg::HilSensor&, uint64_t i) -> std::optional<msg::HilActuatorControls> {
    if (i >= 50) return std::nullopt;
    return actuators(0.0, false);
  });
  Process gone(dead.sim_args({"--duration", "60", "--lockstep", "--no-vio"}));
  EXPECT_EQ(gone.wait(60s), 1) << gone.err();
  EXPECT_NE(gone.err().find("ending the session"), std::string::npos) << gone.err();
  EXPECT_NE(gone.err().find("restart"), std::string::npos) << gone.err();
  const auto j = last_json(gone.out());
  EXPECT_EQ(j["end"], "flight_stack_gone");
  EXPECT_LT(j["sim_time_s"].get<double>(), 30.0);
}

}  // namespace
}  // namespace hitl
