#include "engine/replay/recorded_session.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <memory>
#include <optional>

#include "base/contract/session_status.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/message_set.h"
#include "base/mavlink/messages.h"
#include "engine/mavlink/tlog.h"
#include "engine/mavlink/tlog_timeline.h"

namespace hitl::replay {
namespace msg = mavlink::msg;

double RecordedSession::duration_s() const {
  if (steps.size() < 2) return 0;
  return static_cast<double>(steps.back().sensor_time_usec - steps.front().sensor_time_usec) * 1e-6;
}

namespace {

/// The session's own messages to its clients (status, truth, fault announcements): never sent to the board.
bool to_clients_only(const mavlink::Frame& f) {
  return f.is<msg::NamedValueFloat>() || f.is<msg::NamedValueInt>() || f.is<msg::Statustext>() ||
         (f.is<msg::Odometry>() && f.compid != kVioComponentId);
}

}  // namespace

Expected<RecordedSession> load_recording(const std::string& path, uint64_t max_bytes) {
  const std::string name = "recording '" + path + "'";
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return Error::input(name + ": " + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) return Error::input(name + " is not a regular file");
  if (static_cast<uint64_t>(st.st_size) > max_bytes)
    return Error::input(name + " is " + std::to_string(static_cast<uint64_t>(st.st_size) >> 20) + " MiB, more than the " +
                        std::to_string(max_bytes >> 20) + " MiB a replay reads (about 50 minutes at 250 Hz): record shorter sessions");
  const auto messages = mavlink::MessageSet::compiled();
  // First the identities: the board is who sends HIL_ACTUATOR_CONTROLS, the simulator who sends
  // HIL_SENSOR (the board's HEARTBEATs come before its first answer).
  std::optional<uint8_t> board_sysid;
  {
    auto first = mavlink::TlogReader::open(path);
    if (!first) return first.error().prefixed(name + ": ");
    mavlink::FrameParser parser(messages);
    mavlink::TlogRecord record;
    while (!board_sysid && first->next(record))
      parser.parse_datagram(record.frame, [&](const mavlink::Frame& f) {
        if (f.is<msg::HilActuatorControls>() && !board_sysid) board_sysid = f.sysid;
      });
  }
  auto opened = mavlink::TlogReader::open(path);
  if (!opened) return opened.error().prefixed(name + ": ");
  // Its clock checked as it is read (tlog_timeline.h): a replay waits out the recorded gaps.
  auto reader = std::make_unique<mavlink::TlogTimeline>(std::move(opened.value()));
  mavlink::FrameParser parser(messages);
  RecordedSession s;
  // To the board after the last step's datagram left (the session sends VIO and truth ODOMETRY
  // after it): a client's frames forwarded at the next step's start, so in the next datagram, before
  // its HIL_SENSOR. Also what came before the first HIL_SENSOR.
  std::vector<OutgoingFrame> carried;
  bool datagram_left = true;
  mavlink::TimedRecord timed;
  const mavlink::TlogRecord& record = timed.record;
  uint64_t unparsed = 0;
  while (reader->next(timed)) {
    bool parsed = false;
    parser.parse_datagram(record.frame, [&](const mavlink::Frame& f) {
      parsed = true;
      ++s.frames;
      if (f.is<msg::HilActuatorControls>()) {
        if (f.sysid != *board_sysid) return;
        const auto m = f.as<msg::HilActuatorControls>();
        ActuatorSample a;
        a.time_usec = m.time_usec;
        a.step = static_cast<int64_t>(s.steps.size()) - 1;
        for (std::size_t i = 0; i < 4; ++i) a.controls[i] = m.controls[i];
        a.mode = m.mode;
        s.actuators.push_back(a);
        return;
      }
      if (f.is<msg::HilSensor>()) {
        if (s.steps.empty()) s.simulator_sysid = f.sysid;
        if (f.sysid == s.simulator_sysid) {
          RecordedStep step;
          step.sensor_time_usec = f.as<msg::HilSensor>().time_usec;
          step.t_unix_us = record.time_unix_us;
          step.frames = std::move(carried);
          carried.clear();
          step.frames.push_back({Destination::Hil, {f.bytes().begin(), f.bytes().end()}});
          s.steps.push_back(std::move(step));
          datagram_left = false;
          return;
        }
      }
      if (board_sysid && f.sysid == *board_sysid) return;  // the board's own telemetry and answers
      const bool own = !s.steps.empty() && f.sysid == s.simulator_sysid;
      if (own && f.is<msg::Odometry>()) datagram_left = true;  // VIO and truth go out after the step's datagram
      if (own && to_clients_only(f)) return;
      OutgoingFrame out{f.is<msg::Odometry>() ? Destination::Vio : Destination::Hil, {f.bytes().begin(), f.bytes().end()}};
      if (out.to == Destination::Vio && f.compid != kVioComponentId) return;  // truth to clients
      if (out.to == Destination::Vio) ++s.vio_frames;
      else ++s.other_frames;
      const bool to_this_step = !s.steps.empty() && (out.to == Destination::Vio || !datagram_left);
      (to_this_step ? s.steps.back().frames : carried).push_back(std::move(out));
    });
    if (!parsed) ++unparsed;
  }
  const auto& stats = reader->stats();
  if (s.frames == 0 && (stats.skipped_bytes > 0 || unparsed > 0))
    return Error::input(name + " is not a .tlog: no MAVLink frame behind an 8-byte timestamp in its " +
                        std::to_string(st.st_size) + " bytes");
  if (stats.records == 0) return Error::input(name + " is empty");
  if (stats.truncated > 0 || stats.skipped_bytes > 0 || unparsed > 0)
    return Error::input(name + " is cut off or corrupt (" + std::to_string(stats.truncated) + " record(s) cut off at the end, " +
                        std::to_string(stats.skipped_bytes) + " bytes that are no record, " + std::to_string(unparsed) +
                        " records that are no valid frame): replay needs a whole recording");
  if (const auto& t = reader->timeline(); t.segments > 1 || t.set_aside_records > 0)
    return Error::input(name + "'s clock jumps (" + std::to_string(t.segments) + " segments, " + std::to_string(t.set_aside_records) +
                        " records whose stamp jumped alone; a jump back, or ahead more than 60 s, starts a segment): "
                        "replay needs one whole recording");
  if (s.steps.empty())
    return Error::input(name + " holds no HIL_SENSOR (" + std::to_string(s.frames) +
                        " frames): not a hitl sim recording (hitl sim --record FILE.tlog records one)");
  return s;
}

}  // namespace hitl::replay
