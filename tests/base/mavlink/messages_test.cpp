// Typed messages: CRC_EXTRA and lengths agree with their own field lists, and every
// message survives encode -> parse -> decode with values in every field.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/messages.h"
#include "base/mavlink/typed_codec.h"

namespace hitl::mavlink {
namespace {

template <class T>
void randomize(T& v, std::mt19937& rng) {
  if constexpr (std::is_floating_point_v<T>) v = std::uniform_real_distribution<T>(-1e6, 1e6)(rng);
  else if constexpr (std::is_same_v<T, char>) v = static_cast<char>('a' + rng() % 26);
  else v = static_cast<T>(rng());
}
template <class T, std::size_t N>
void randomize(std::array<T, N>& a, std::mt19937& rng) {
  for (auto& v : a) randomize(v, rng);
}

template <class M>
M random_message(std::mt19937& rng) {
  M m;
  std::apply([&](const auto&... f) { (randomize(m.*(f.member), rng), ...); }, M::fields());
  return m;
}

template <class M>
bool equal_fields(const M& a, const M& b) {
  return std::apply([&](const auto&... f) { return ((std::memcmp(&(a.*(f.member)), &(b.*(f.member)), sizeof(a.*(f.member))) == 0) && ...); },
                    M::fields());
}

template <class M>
void check_message() {
  SCOPED_TRACE(std::string(M::kName));
  const MessageDesc desc = describe<M>();
  EXPECT_EQ(compute_crc_extra(desc), M::kCrcExtra);
  MessageDesc resorted = desc;
  assign_wire_order(resorted);
  EXPECT_EQ(resorted.min_length, M::kMinLength);
  EXPECT_EQ(resorted.max_length, M::kMaxLength);
  for (std::size_t i = 0; i < desc.fields.size(); ++i) EXPECT_EQ(resorted.fields[i].name, desc.fields[i].name);

  std::mt19937 rng(M::kId);
  const M sent = random_message<M>(rng);
  FrameEncoder encoder(42, 7);
  FrameBuffer buf;
  const std::size_t n = encoder.encode(sent, buf);
  ASSERT_GT(n, 0u);
  const auto set = MessageSet::compiled();
  FrameParser parser(set);
  int frames = 0;
  parser.parse_datagram({buf.data(), n}, [&](const Frame& f) {
    ++frames;
    EXPECT_EQ(f.msgid, M::kId);
    EXPECT_EQ(f.sysid, 42);
    EXPECT_EQ(f.compid, 7);
    ASSERT_NE(f.desc, nullptr);
    EXPECT_TRUE(equal_fields(sent, f.as<M>()));
  });
  EXPECT_EQ(frames, 1);
  EXPECT_EQ(parser.stats().crc_errors, 0u);
}

template <class... Ms>
void check_all(TypeList<Ms...>) {
  (check_message<Ms>(), ...);
}

TEST(Messages, EveryCompiledMessageIsConsistentAndRoundTrips) { check_all(msg::All{}); }

TEST(Messages, WellKnownCrcExtraAndIds) {
  // Values every MAVLink implementation agrees on.
  EXPECT_EQ(msg::Heartbeat::kCrcExtra, 50);
  EXPECT_EQ(msg::HilSensor::kId, 107u);
  EXPECT_EQ(msg::HilSensor::kCrcExtra, 108);
  EXPECT_EQ(msg::HilGps::kCrcExtra, 124);
  EXPECT_EQ(msg::HilActuatorControls::kCrcExtra, 47);
  EXPECT_EQ(msg::CommandLong::kCrcExtra, 152);
  EXPECT_EQ(msg::Odometry::kId, 331u);
  EXPECT_EQ(msg::Odometry::kCrcExtra, 91);
  EXPECT_EQ(msg::HilSensor::kMinLength, 64);
  EXPECT_EQ(msg::HilSensor::kMaxLength, 65);
}

TEST(Messages, CompiledSetHasAllAndLooksUpByNameOrId) {
  const auto set = MessageSet::compiled();
  EXPECT_GE(set.size(), 40u);
  ASSERT_NE(set.lookup("hil_sensor"), nullptr);
  EXPECT_EQ(set.lookup("hil_sensor")->id, 107u);
  EXPECT_EQ(set.lookup("331")->name, "ODOMETRY");
  EXPECT_EQ(set.lookup("NOPE"), nullptr);
}

}  // namespace
}  // namespace hitl::mavlink
