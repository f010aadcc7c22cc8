#include "engine/telemetry/dsp_hitl_meter.h"

namespace hitl::telemetry {

DspHitlExpectedRates dsp_hitl_expected_rates(double mag_published_hz, double baro_published_hz) {
  DspHitlExpectedRates r;
  r.imu_received_hz = rate_hz_from_period_us(kHilImuPublishPeriod_us);
  r.imu_published_hz = r.imu_received_hz;
  r.mag_baro_received_hz = rate_hz_from_period_us(kHilMagBaroPublishPeriod_us);
  r.mag_published_hz = mag_published_hz;
  r.baro_published_hz = baro_published_hz;
  return r;
}

DspHitlExpectedRates spec_dsp_hitl_expected_rates() { return dsp_hitl_expected_rates(kSpecMagRate_hz, kSpecBaroRate_hz); }
namespace {

std::array<uint64_t, 5> counts(const target::DspHitlCounters& c) {
  return {c.hil_imu_received, c.imu_published, c.hil_mag_baro_received, c.mag_published, c.baro_published};
}

}  // namespace

void DspHitlMeter::on_report(const target::DspHitlStatusReport& report, double t_s) {
  // A counter that went back was cleared (dsp_hitl clear, or the board restarted): start over.
  if (!polls_.empty()) {
    const auto before = counts(polls_.back().report.counters), now = counts(report.counters);
    for (std::size_t i = 0; i < now.size(); ++i)
      if (now[i] < before[i]) polls_.clear();
  }
  polls_.push_back({t_s, report});
  while (polls_.size() > kRateWindowPolls) polls_.pop_front();
  unavailable_.clear();
}

void DspHitlMeter::on_unavailable(const std::string& reason) { unavailable_ = reason; }

DspHitlView DspHitlMeter::view(double now_s) const {
  DspHitlView v;
  if (!unavailable_.empty()) {
    v.state = DspHitlView::State::Unavailable;
    v.reason = unavailable_;
  } else if (!polls_.empty()) {
    v.state = DspHitlView::State::Available;
  }
  namespace label = target::dsp_hitl_label;
  static constexpr const char* kNames[] = {label::kImuReceived, label::kImuPublished, label::kMagBaroReceived,
                                           label::kMagPublished, label::kBaroPublished};
  const std::array<double, 5> expected = {expected_.imu_received_hz, expected_.imu_published_hz,
                                          expected_.mag_baro_received_hz, expected_.mag_published_hz,
                                          expected_.baro_published_hz};
  for (std::size_t i = 0; i < v.counters.size(); ++i) {
    v.counters[i].name = kNames[i];
    v.counters[i].expected_hz = expected[i];
  }
  if (polls_.empty()) return v;
  const Poll& last = polls_.back();
  v.running = last.report.running;
  v.age_s = now_s - last.t_s;
  const auto now_counts = counts(last.report.counters);
  for (std::size_t i = 0; i < v.counters.size(); ++i) v.counters[i].count = now_counts[i];
  if (polls_.size() >= 2) {
    const Poll& first = polls_.front();
    const auto first_counts = counts(first.report.counters);
    const auto previous_counts = counts(polls_[polls_.size() - 2].report.counters);
    const double dt_s = last.t_s - first.t_s;
    for (std::size_t i = 0; i < v.counters.size(); ++i) {
      if (dt_s > 0) v.counters[i].rate_hz = static_cast<double>(now_counts[i] - first_counts[i]) / dt_s;
      v.counters[i].stalled = now_counts[i] == previous_counts[i];
    }
  }
  return v;
}

}  // namespace hitl::telemetry
