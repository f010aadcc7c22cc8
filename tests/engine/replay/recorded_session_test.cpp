// load_recording (engine/replay/recorded_session.h) on recordings written here: what becomes a
// step and what is left out, and the bad files, each refused naming the file and the problem.
#include "engine/replay/recorded_session.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "base/contract/session_status.h"
#include "base/mavlink/enums.h"
#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/messages.h"
#include "engine/mavlink/tlog.h"
#include "tests/support/process.h"

namespace hitl::replay {
namespace {
namespace msg = mavlink::msg;

class Writer {
 public:
  explicit Writer(const std::string& path) : tlog_(*mavlink::TlogWriter::open(path)) {}
  template <class M>
  void write(mavlink::FrameEncoder& enc, const M& m) {
    mavlink::FrameBuffer buf;
    const auto n = enc.encode(m, buf);
    tlog_.write(t_us_ += 100, {buf.data(), n});
  }
  void flush() { tlog_.flush(); }

 private:
  mavlink::TlogWriter tlog_;
  uint64_t t_us_ = 1700000000000000;
};

std::string path_in_temp(const char* name) { return test::temp_dir() + "/" + name; }

TEST(RecordedSession, StepsHoldWhatWentToTheBoardAndAnswersTheirStep) {
  const auto path = path_in_temp("session.tlog");
  {
    Writer w(path);
    mavlink::FrameEncoder sim(kSimulatorSystemId, kSimulatorComponentId), vio(kSimulatorSystemId, kVioComponentId),
        board(1, 1), gcs(mavlink::kGcsSystemId, 190), client(mavlink::kGcsSystemId, 191);
    msg::Heartbeat hb;
    w.write(board, hb);  // the board's telemetry: left out
    for (uint64_t k = 1; k <= 3; ++k) {
      msg::HilSensor s;
      s.time_usec = k * 4000;
      w.write(sim, s);
      msg::HilGps g;
      g.time_usec = k * 4000;
      w.write(sim, g);
      msg::CommandLong c;  // the pilot's command: to the board
      w.write(gcs, c);
      msg::Odometry o;  // VIO
      o.time_usec = k * 4000;
      w.write(vio, o);
      msg::Odometry truth;  // ground truth to clients: left out
      w.write(sim, truth);
      msg::NamedValueFloat status;  // the session's status to clients: left out
      w.write(sim, status);
      if (k == 1) {  // a client's sticks, forwarded at the next step's start: in its datagram, first
        msg::ManualControl m;
        w.write(client, m);
      }
      msg::HilActuatorControls a;
      a.time_usec = k * 4000;
      a.controls[2] = 0.5f * static_cast<float>(k);
      w.write(board, a);
    }
    w.flush();
  }
  auto s = load_recording(path);
  ASSERT_TRUE(s) << s.error().message;
  ASSERT_EQ(s->steps.size(), 3u);
  EXPECT_EQ(s->simulator_sysid, kSimulatorSystemId);
  EXPECT_EQ(s->steps[1].sensor_time_usec, 8000u);
  ASSERT_EQ(s->steps[0].frames.size(), 4u);  // HIL_SENSOR, HIL_GPS, COMMAND_LONG, ODOMETRY
  EXPECT_EQ(s->steps[0].frames[0].to, Destination::Hil);
  EXPECT_EQ(s->steps[0].frames[3].to, Destination::Vio);
  ASSERT_EQ(s->steps[1].frames.size(), 5u);  // MANUAL_CONTROL, HIL_SENSOR, HIL_GPS, COMMAND_LONG, ODOMETRY
  EXPECT_EQ(s->steps[1].frames[0].bytes[7], 69);  // MANUAL_CONTROL's id
  EXPECT_EQ(s->steps[1].frames[1].bytes[7], 107);  // HIL_SENSOR's id
  EXPECT_EQ(s->vio_frames, 3u);
  EXPECT_EQ(s->other_frames, 7u);
  ASSERT_EQ(s->actuators.size(), 3u);
  EXPECT_EQ(s->actuators[2].step, 2);
  EXPECT_EQ(s->actuators[2].time_usec, 12000u);
  EXPECT_FLOAT_EQ(s->actuators[2].controls[2], 1.5f);
  EXPECT_NEAR(s->duration_s(), 0.008, 1e-12);
}

void expect_refused(const std::string& path, const std::string& words, uint64_t max_bytes = kMaxRecordingBytes) {
  auto s = load_recording(path, max_bytes);
  ASSERT_FALSE(s) << path;
  EXPECT_EQ(s.error().kind, ErrorKind::Input);
  EXPECT_NE(s.error().message.find(path), std::string::npos) << s.error().message;
  EXPECT_NE(s.error().message.find(words), std::string::npos) << s.error().message;
}

TEST(RecordedSession, BadFilesAreRefusedNamingTheFileAndTheProblem) {
  const auto dir = test::temp_dir();
  expect_refused(dir + "/missing.tlog", "No such file");
  expect_refused(dir, "not a regular file");
  std::ofstream(dir + "/empty.tlog").close();
  expect_refused(dir + "/empty.tlog", "is empty");
  std::ofstream(dir + "/text.tlog") << "this is a trajectory, not a telemetry log\n";
  expect_refused(dir + "/text.tlog", "is not a .tlog");
  {
    Writer w(dir + "/beats.tlog");
    mavlink::FrameEncoder board(1, 1);
    for (int i = 0; i < 5; ++i) w.write(board, msg::Heartbeat{});
    w.flush();
  }
  expect_refused(dir + "/beats.tlog", "holds no HIL_SENSOR (5 frames)");
  {
    Writer w(dir + "/cut.tlog");
    mavlink::FrameEncoder sim(kSimulatorSystemId, kSimulatorComponentId);
    for (int i = 0; i < 5; ++i) w.write(sim, msg::HilSensor{});
    w.flush();
  }
  std::filesystem::resize_file(dir + "/cut.tlog", std::filesystem::file_size(dir + "/cut.tlog") - 7);
  expect_refused(dir + "/cut.tlog", "cut off or corrupt (1 record(s) cut off at the end");
  std::ofstream(dir + "/huge.tlog").close();
  std::filesystem::resize_file(dir + "/huge.tlog", 3ull << 20);  // sparse: no disk used
  expect_refused(dir + "/huge.tlog", "is 3 MiB, more than the 2 MiB", 2ull << 20);
}

}  // namespace
}  // namespace hitl::replay
