#include "engine/telemetry/traffic_stats.h"

#include <algorithm>

namespace hitl::telemetry {

const MessageSummary* TrafficSummary::message(std::string_view name) const {
  for (const auto& m : messages)
    if (m.name == name) return &m;
  return nullptr;
}

void TrafficStats::restart(int64_t start_ns) { *this = TrafficStats(start_ns); }

TrafficStats::Bound TrafficStats::on_frame(const mavlink::Frame& frame, const std::string& source, int64_t t_ns) {
  ++frames_;
  Bound hit = Bound::None;
  auto meter = meters_.find(frame.msgid);
  if (meter == meters_.end() && meters_.size() < kMaxMessageIds) meter = meters_.try_emplace(frame.msgid).first;
  if (meter != meters_.end()) {
    auto& m = meter->second;
    if (m.count == 0) m.name = frame.desc ? frame.desc->name : "#" + std::to_string(frame.msgid);
    ++m.count;
    ++m.window_count;
    m.bytes += frame.raw_len;
    m.gaps.arrival(t_ns);
  } else if (untracked_id_frames_++ == 0) {
    hit = Bound::MessageIds;
  }
  auto key = std::make_tuple(source, frame.sysid, frame.compid);
  auto tracker = sources_.find(key);
  if (tracker == sources_.end() && sources_.size() < kMaxSources) tracker = sources_.try_emplace(std::move(key)).first;
  if (tracker != sources_.end()) tracker->second.observe(frame.seq);
  else if (untracked_source_frames_++ == 0 && hit == Bound::None) hit = Bound::Sources;
  return hit;
}

void TrafficStats::new_segment(int64_t end_ns, int64_t start_ns) {
  closed_duration_ns_ += std::max(0.0, static_cast<double>(end_ns) - static_cast<double>(start_ns_));
  for (auto& [id, m] : meters_) m.gaps.end_segment(end_ns);
  for (auto& [key, tracker] : sources_) tracker.restart();  // a joined log's sequence starts over
  ++segments_;
  start_ns_ = window_start_ns_ = start_ns;
}

void TrafficStats::roll(int64_t now_ns) {
  const double window_s = static_cast<double>(now_ns - window_start_ns_) * 1e-9;
  for (auto& [id, m] : meters_) {
    m.recent_rate_hz = window_s > 0 ? static_cast<double>(m.window_count) / window_s : 0.0;
    m.window_count = 0;
  }
  window_start_ns_ = now_ns;
}

TrafficSummary TrafficStats::summary(int64_t now_ns, const mavlink::ParserStats& parser) const {
  TrafficSummary s;
  s.duration_s = (closed_duration_ns_ + std::max(0.0, static_cast<double>(now_ns) - static_cast<double>(start_ns_))) * 1e-9;
  s.segments = segments_;
  s.frames = frames_;
  s.datagrams = datagrams_;
  s.untracked_id_frames = untracked_id_frames_;
  s.untracked_source_frames = untracked_source_frames_;
  s.parser = parser;
  for (const auto& [id, m] : meters_) {
    MessageSummary ms;
    ms.id = id;
    ms.name = m.name;
    ms.count = m.count;
    ms.bytes = m.bytes;
    ms.gap = m.gaps.summary();
    ms.recent_rate_hz = m.recent_rate_hz;
    ms.rate_hz = m.gaps.rate_hz(now_ns);
    ms.bytes_per_s = s.duration_s > 0 ? static_cast<double>(m.bytes) / s.duration_s : 0.0;
    s.messages.push_back(std::move(ms));
  }
  for (const auto& [key, tracker] : sources_) {
    SourceSummary src;
    src.address = std::get<0>(key);
    src.sysid = std::get<1>(key);
    src.compid = std::get<2>(key);
    src.seq = tracker.stats();
    s.sources.push_back(std::move(src));
  }
  return s;
}

}  // namespace hitl::telemetry
