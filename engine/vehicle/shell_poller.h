// The board's dsp_hitl counters for a dashboard, on its own thread and its own link: runs
// `qshell dsp_hitl status` through the MAVLink shell about once a second and reads it with the
// status text's own parser (base/contract/dsp_hitl_status.h), into a DspHitlMeter. The same thread
// runs one-shot shell commands an operator asks for, so two conversations never interleave on the
// shell; their output goes to a callback.
#pragma once

#include <atomic>
#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include "engine/telemetry/dsp_hitl_meter.h"
#include "engine/vehicle/vehicle_link.h"

namespace hitl::vehicle {

inline constexpr const char* kDspHitlStatusCommand = "qshell dsp_hitl status";

class ShellPoller {
 public:
  /// `ok` false: the command did not finish (`output` says why).
  using OutputSink = std::function<void(const std::string& command, bool ok, const std::string& output)>;

  ShellPoller(LinkOptions options, const telemetry::DspHitlExpectedRates& expected, double poll_period_s, OutputSink output);
  ~ShellPoller();  ///< stops and joins
  ShellPoller(const ShellPoller&) = delete;
  ShellPoller& operator=(const ShellPoller&) = delete;

  telemetry::DspHitlView dsp_hitl() const;
  /// Queues one command line; its output goes to the sink.
  void run_command(const std::string& line);
  void stop();

 private:
  void run();
  void poll_dsp_hitl(class ShellClient& shell);

  LinkOptions options_;
  double poll_period_s_;
  OutputSink output_;
  std::atomic<bool> stop_{false};
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::string> commands_;
  telemetry::DspHitlMeter meter_;
  std::thread thread_;
};

}  // namespace hitl::vehicle
