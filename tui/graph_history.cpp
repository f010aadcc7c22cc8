#include "tui/graph_history.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hitl::tui {
namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
double finite_or_nan(const std::optional<double>& v) { return v && std::isfinite(*v) ? *v : kNaN; }
}  // namespace

void SampleRing::push(double value) {
  if (capacity_ == 0) return;
  if (values_.size() < capacity_) {
    values_.push_back(value);
    return;
  }
  values_[next_] = value;
  next_ = (next_ + 1) % capacity_;
}

std::vector<double> SampleRing::values() const {
  std::vector<double> out;
  out.reserve(values_.size());
  out.insert(out.end(), values_.begin() + static_cast<std::ptrdiff_t>(next_), values_.end());
  out.insert(out.end(), values_.begin(), values_.begin() + static_cast<std::ptrdiff_t>(next_));
  return out;
}

GraphHistory::GraphHistory(double window_s, double sample_hz)
    : window_s_(window_s),
      period_s_(1.0 / sample_hz),
      capacity_(static_cast<std::size_t>(std::lround(window_s * sample_hz))),
      truth_(capacity_),
      estimate_(capacity_),
      tracking_(capacity_) {}

void GraphHistory::add(double now_s, const DashboardModel& m, std::optional<double> tracking_error_m) {
  // How many sample periods have passed: 1 % slack, so a frame due every period that arrives a hair
  // early still samples; a frame several periods on (a session faster than real time) holds its
  // values for each of them, so the axis stays even on the caller's clock; at most one window.
  std::size_t periods = 1;
  double next_last_s = now_s;  // the first sample, or one after the clock went back (a new session)
  if (last_s_ >= 0 && now_s > last_s_ - period_s_) {  // (further back: the clock went back)
    const double elapsed = (now_s - last_s_) / period_s_;
    if (elapsed < 0.99) return;
    periods = static_cast<std::size_t>(std::min(static_cast<double>(capacity_), std::floor(elapsed + 0.01)));
    if (periods < capacity_) next_last_s = last_s_ + static_cast<double>(periods) * period_s_;  // no drift
  }
  last_s_ = next_last_s;
  for (std::size_t i = 0; i < periods; ++i) push_sample(m, tracking_error_m);
}

void GraphHistory::push_sample(const DashboardModel& m, std::optional<double> tracking_error_m) {
  truth_.push(m.vehicle ? finite_or_nan(m.vehicle->truth_altitude_m) : kNaN);
  estimate_.push(m.vehicle ? finite_or_nan(m.vehicle->altitude_m) : kNaN);
  tracking_.push(finite_or_nan(tracking_error_m));
  for (const auto& row : m.paths.rows) {
    auto it = std::find_if(rates_.begin(), rates_.end(), [&](const Rate& r) { return r.name == row.name; });
    if (it == rates_.end()) {
      if (rates_.size() >= kMaxRateSeries) continue;
      rates_.push_back({row.name, row.expected_hz, SampleRing(capacity_)});
      // Joined late: NaN for the samples before it, so every series has the same time axis.
      for (std::size_t i = 1; i < truth_.size(); ++i) rates_.back().samples.push(kNaN);
      it = rates_.end() - 1;
    }
    it->expected_hz = row.expected_hz;
  }
  for (auto& r : rates_) {
    auto row = std::find_if(m.paths.rows.begin(), m.paths.rows.end(), [&](const PathRow& p) { return p.name == r.name; });
    r.samples.push(row != m.paths.rows.end() && std::isfinite(row->rate_hz) ? row->rate_hz : kNaN);
  }
}

GraphsPanel GraphHistory::panel() const {
  GraphsPanel p;
  p.window_s = window_s_;
  p.capacity = capacity_;
  p.truth_altitude_m = truth_.values();
  p.estimate_altitude_m = estimate_.values();
  p.tracking_error_m = tracking_.values();
  if (std::none_of(p.tracking_error_m.begin(), p.tracking_error_m.end(), [](double v) { return std::isfinite(v); }))
    p.tracking_error_m.clear();
  for (const auto& r : rates_) p.rates.push_back({r.name, r.expected_hz, r.samples.values()});
  return p;
}

}  // namespace hitl::tui
