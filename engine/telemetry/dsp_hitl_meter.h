// The board's dsp_hitl counters over time (the text of `qshell dsp_hitl status`, polled about once a
// second): each counter's rate from its change over the last few polls (kRateWindowPolls: one
// count more or less on the 10 Hz baro is 2 %, not 10 %), and a stall mark when a counter did not
// change between the last two polls. Or, when the board cannot answer (PX4 SITL has no dsp_hitl, no
// shell, a garbled reply), the reason.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>

#include "base/contract/data_rates.h"
#include "base/contract/dsp_hitl_status.h"

namespace hitl::telemetry {

/// The rates the spec's table gives each counter (board clock), filled by the caller from its
/// configuration: hil_sensor_imu 250 Hz, hil_sensor_mag_baro 100 Hz, sensor_mag and sensor_baro at
/// the simulator's mag and baro rates.
struct DspHitlExpectedRates {
  double imu_received_hz = 0;
  double imu_published_hz = 0;
  double mag_baro_received_hz = 0;
  double mag_published_hz = 0;
  double baro_published_hz = 0;
};

/// The spec's split rates (base/contract/data_rates.h) with sensor_mag and sensor_baro published at
/// the given rates (the simulator's mag and baro rates; the spec's table: 50 Hz and 10 Hz).
DspHitlExpectedRates dsp_hitl_expected_rates(double mag_published_hz, double baro_published_hz);
/// The spec's table throughout (kSpecMagRate_hz, kSpecBaroRate_hz): for whoever does not know the
/// simulator that feeds the board (hitl doctor, hitl bridge).
DspHitlExpectedRates spec_dsp_hitl_expected_rates();

struct DspHitlCounterView {
  const char* name = "";           ///< the status text's label
  uint64_t count = 0;
  std::optional<double> rate_hz;   ///< over the last polls; none before the second
  double expected_hz = 0;
  bool stalled = false;            ///< did not change between the last two polls
};

struct DspHitlView {
  enum class State { Waiting, Available, Unavailable };
  State state = State::Waiting;
  std::string reason;              ///< Unavailable: why ("no dsp_hitl on this board: ...")
  bool running = false;
  std::array<DspHitlCounterView, 5> counters{};
  double age_s = -1;               ///< since the last good poll; -1 before the first
};

class DspHitlMeter {
 public:
  static constexpr std::size_t kRateWindowPolls = 5;

  explicit DspHitlMeter(const DspHitlExpectedRates& expected) : expected_(expected) {}
  void on_report(const target::DspHitlStatusReport& report, double t_s);
  /// The poll failed: the board has no dsp_hitl, or its shell did not answer.
  void on_unavailable(const std::string& reason);
  DspHitlView view(double now_s) const;

 private:
  struct Poll {
    double t_s = 0;
    target::DspHitlStatusReport report;
  };
  DspHitlExpectedRates expected_;
  std::deque<Poll> polls_;  ///< the last kRateWindowPolls, oldest first, counters never going back
  std::string unavailable_;
};

}  // namespace hitl::telemetry
