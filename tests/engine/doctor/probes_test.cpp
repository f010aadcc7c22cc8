// The doctor's probes over loopback (engine/doctor/host_probe, session_probe): a UDP port held or
// free, and a session's client port heard or absent. Their sockets are engine/net's.
#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <thread>
#include <vector>

#include "base/common/clock.h"
#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/heartbeat.h"
#include "base/mavlink/message_set.h"
#include "engine/doctor/host_probe.h"
#include "engine/doctor/session_probe.h"
#include "engine/net/open_link.h"

namespace hitl::doctor {
namespace {

std::unique_ptr<net::Link> listener(const std::string& address = "127.0.0.1") {
  net::LinkSettings settings;
  settings.name = "test session";
  net::LinkSpec spec;  // udpin:ADDRESS:0 (the grammar takes no port 0: an ephemeral one for the test)
  spec.kind = net::LinkSpec::Kind::UdpIn;
  spec.host = address;
  auto link = net::open_link(spec, settings);
  EXPECT_TRUE(link.ok()) << link.error().message;
  return std::move(link.value());
}

TEST(DoctorProbes, AUdpPortHeldOrFree) {
  auto held = listener("0.0.0.0");
  const uint16_t port = held->local_address()->port();
  const PortProbe taken = probe_udp_port(port, "HIL");
  EXPECT_TRUE(taken.taken);
  EXPECT_TRUE(taken.error.empty()) << taken.error;
  held.reset();
  const PortProbe free = probe_udp_port(port, "HIL");
  EXPECT_FALSE(free.taken);
  EXPECT_TRUE(free.error.empty()) << free.error;
}

TEST(DoctorProbes, ASessionsClientPortIsHeardAndNoneEndsAtOnce) {
  // A stand-in session: answers each HEARTBEAT heard with its own.
  auto session = listener();
  const uint16_t port = session->local_address()->port();
  std::atomic<bool> stop{false};
  std::thread answering([&] {
    const auto messages = mavlink::MessageSet::compiled();
    mavlink::FrameParser parser(messages);
    mavlink::FrameEncoder encoder(1, 1);
    while (!stop.load()) {
      if (!session->wait_readable(20)) continue;
      session->drain(parser, [&](const mavlink::Frame&) {
        mavlink::FrameBuffer frame;
        const std::size_t n = encoder.encode(mavlink::gcs_heartbeat(), frame);
        (void)session->send({frame.data(), n});
      });
    }
  });
  std::vector<uint8_t> heard;
  probe_session(port, 0.5, [&](const mavlink::Frame& f, double) { heard.push_back(f.sysid); });
  stop = true;
  answering.join();
  ASSERT_FALSE(heard.empty());
  EXPECT_EQ(heard.front(), 1);

  session.reset();  // nothing listens there now
  const double start_s = monotonic_s();
  probe_session(port, 5.0, [&](const mavlink::Frame&, double) { ADD_FAILURE() << "no session, no frame"; });
  EXPECT_LT(monotonic_s() - start_s, 1.0);
}

}  // namespace
}  // namespace hitl::doctor
