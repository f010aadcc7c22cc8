// hitl sim --px4 DIR: PX4 SITL that the session starts, watches and stops (issue 38). It finds the
// build, claims a free instance by listening on that instance's simulator port (so two sessions on
// one machine never get the same one), starts PX4 there with the vehicle's parameters and the
// user's, shows PX4's console warnings and errors as the session's events, ends the session when
// PX4 exits, refuses a parameter or does not connect in time (with its last console lines), and
// stops it at the end: SIGTERM once it has run on sensors, SIGKILL before (PX4 ignores SIGTERM until
// its first HIL_SENSOR). PX4 runs in its own process group and dies with hitl (PR_SET_PDEATHSIG).
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "engine/hil/session_config.h"
#include "engine/hil/session_events.h"
#include "engine/hil/stack_link.h"
#include "engine/px4/px4_build.h"
#include "engine/px4/px4_instance.h"
#include "engine/px4/px4_process.h"

namespace hitl::hil {

class Px4Launch {
 public:
  /// Opens the session's stack link for PX4 instance `i` (StackPeer::decide(config, i), StackLink::open).
  using OpenStack = std::function<Expected<std::unique_ptr<StackLink>>(const px4::Px4Instance& i)>;

  /// Finds the build (an input Error saying what is missing), claims the first free instance with
  /// `open_stack` (its link goes to `stack`) and prepares PX4's working folder. Nothing starts yet.
  static Expected<std::unique_ptr<Px4Launch>> claim(const SessionConfig& config, const OpenStack& open_stack,
                                                    std::unique_ptr<StackLink>& stack);
  ~Px4Launch();
  Px4Launch(const Px4Launch&) = delete;
  Px4Launch& operator=(const Px4Launch&) = delete;

  /// Starts PX4 (the session's run does, once everything else is open).
  Status start(EventSink& events);
  /// PX4's new console lines (warnings and errors to `events`, at most kMaxLinesPerCheck each
  /// time); an Error when the session must end: PX4 exited, refused a parameter, or has not
  /// connected within the timeout. `link_closed`: the simulator link is gone (PX4 is given a moment
  /// to exit, so that the message says how it ended).
  std::optional<Error> check(EventSink& events, bool connected, bool link_closed = false);
  /// Stops PX4 (SIGTERM when it ran on sensors, `ran`; SIGKILL otherwise) and waits for it. Once.
  void stop(bool ran, EventSink& events);

  const px4::Px4Build& build() const { return build_; }
  const px4::Px4Instance& instance() const { return options_.instance; }
  const std::string& console_path() const { return options_.console_path; }
  const std::string& work_dir() const { return options_.work_dir; }
  /// "PX4 v1.16.0 (instance 0) started by hitl; console ..., working folder ..."
  std::string describe() const;

  static constexpr std::size_t kMaxLinesPerCheck = 20;
  static constexpr std::size_t kLastLines = 12;  ///< console lines quoted when PX4 ended the session

 private:
  Px4Launch() = default;
  std::string last_lines_text() const;

  px4::Px4Build build_;
  px4::Px4StartOptions options_;
  std::unique_ptr<px4::Px4Process> process_;
  double connect_timeout_s_ = 30;
  double started_s_ = 0;
  bool connected_ = false;
  uint64_t lines_not_shown_ = 0;
  std::optional<Error> refused_;
};

/// The parameters hitl gives PX4 for `config`: the vehicle's (px4_vehicle_params.h), then --px4-param's.
std::vector<px4::Px4Param> px4_params_for(const SessionConfig& config);

}  // namespace hitl::hil
