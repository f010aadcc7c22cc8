#include "base/contract/dsp_hitl_status.h"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <string>

#include "target/core/dsp_hitl.h"

namespace hitl::target {
namespace {

DspHitlCounters spec_counters() {
  DspHitlCounters c;
  c.hil_imu_received = 12453;
  c.imu_published = 12450;
  c.hil_mag_baro_received = 4980;
  c.mag_published = 4975;
  c.baro_published = 995;
  return c;
}

DspHitlCurrent spec_current() {
  DspHitlCurrent cur;
  cur.imu_received = true;
  const float accel[3] = {-0.257F, 0.151F, -9.859F};
  const float gyro[3] = {-0.006F, -0.001F, 0.0F};
  for (int i = 0; i < 3; ++i) {
    cur.accel_FRD_m_s2[i] = accel[i];
    cur.gyro_FRD_rad_s[i] = gyro[i];
  }
  return cur;
}

// The spec's "11. Verify" output, character for character.
const char* const kSpecStatus =
    "Running: yes\n"
    "=== IMU Section ===\n"
    "  HIL sensor_imu received: 12453\n"
    "  IMU updates published: 12450\n"
    "  Current accel (x,y,z): -0.257, 0.151, -9.859\n"
    "  Current gyro (x,y,z): -0.006, -0.001, 0.000\n"
    "=== MAG/BARO Section ===\n"
    "  HIL sensor_mag_baro received: 4980\n"
    "  MAG updates published: 4975\n"
    "  BARO updates published: 995\n";

TEST(DspHitlStatus, ReproducesTheSpecExactly) {
  EXPECT_EQ(dsp_hitl_status_text(true, spec_counters(), spec_current()), kSpecStatus);
}

TEST(DspHitlStatus, NotRunning) {
  const std::string text = dsp_hitl_status_text(false, spec_counters(), spec_current());
  EXPECT_EQ(text.rfind("Running: no\n=== IMU Section ===\n", 0), 0U);
}

TEST(DspHitlStatus, BeforeAnyData) {
  DspHitl d;
  EXPECT_EQ(d.status_text(),
            "Running: no\n"
            "=== IMU Section ===\n"
            "  HIL sensor_imu received: 0\n"
            "  IMU updates published: 0\n"
            "  Current accel (x,y,z): no data\n"
            "  Current gyro (x,y,z): no data\n"
            "=== MAG/BARO Section ===\n"
            "  HIL sensor_mag_baro received: 0\n"
            "  MAG updates published: 0\n"
            "  BARO updates published: 0\n");
}

TEST(DspHitlStatus, ThreeDecimalsNoNegativeZeroNanAsNan) {
  DspHitlCurrent cur = spec_current();
  cur.gyro_FRD_rad_s[0] = -0.0004F;  // rounds to zero
  cur.gyro_FRD_rad_s[1] = -0.0006F;  // rounds to -0.001
  cur.gyro_FRD_rad_s[2] = std::numeric_limits<float>::quiet_NaN();
  cur.accel_FRD_m_s2[0] = 1234.56789F;
  const std::string text = dsp_hitl_status_text(true, spec_counters(), cur);
  EXPECT_NE(text.find("  Current gyro (x,y,z): 0.000, -0.001, nan\n"), std::string::npos) << text;
  EXPECT_NE(text.find("  Current accel (x,y,z): 1234.568, 0.151, -9.859\n"), std::string::npos) << text;
}

TEST(DspHitlStatus, LargeCountersPrintInFull) {
  DspHitlCounters c = spec_counters();
  c.hil_imu_received = 5000000000ULL;  // beyond 32 bits: ~231 days at 250 Hz
  const std::string text = dsp_hitl_status_text(true, c, spec_current());
  EXPECT_NE(text.find("  HIL sensor_imu received: 5000000000\n"), std::string::npos);
}

TEST(DspHitlStatus, BufferFormSnprintfSemantics) {
  const std::size_t length = std::strlen(kSpecStatus);
  char big[1024];
  EXPECT_EQ(format_dsp_hitl_status(big, sizeof big, true, spec_counters(), spec_current()), length);
  EXPECT_STREQ(big, kSpecStatus);

  char small[40];
  EXPECT_EQ(format_dsp_hitl_status(small, sizeof small, true, spec_counters(), spec_current()), length);
  EXPECT_EQ(std::string(small), std::string(kSpecStatus).substr(0, sizeof small - 1));

  EXPECT_EQ(format_dsp_hitl_status(nullptr, 0, true, spec_counters(), spec_current()), length);
}

TEST(DspHitlStatus, FollowsTheRepublisher) {
  DspHitl d;
  d.start();
  HilSensorImu imu;
  imu.accelerometer_m_s2[2] = -9.81F;
  d.on_imu(imu, 1000);
  d.on_imu(imu, 1000);  // same DSP time: received, not published
  HilSensorMagBaro mb;
  mb.fields_updated = HilSensorMagBaro::FIELD_MAG;
  d.on_mag_baro(mb, 2000);
  mb.fields_updated = 0;
  d.on_mag_baro(mb, 12000);
  char buffer[512];
  d.format_status(buffer, sizeof buffer);
  EXPECT_EQ(std::string(buffer), d.status_text());
  EXPECT_EQ(d.status_text(),
            "Running: yes\n"
            "=== IMU Section ===\n"
            "  HIL sensor_imu received: 2\n"
            "  IMU updates published: 1\n"
            "  Current accel (x,y,z): 0.000, 0.000, -9.810\n"
            "  Current gyro (x,y,z): 0.000, 0.000, 0.000\n"
            "=== MAG/BARO Section ===\n"
            "  HIL sensor_mag_baro received: 2\n"
            "  MAG updates published: 1\n"
            "  BARO updates published: 0\n");
}

// --- reading the text back (the dashboard's dsp_hitl panel, polled through the shell) -----------

TEST(DspHitlStatusParse, ReadsTheSpecText) {
  DspHitlStatusReport r;
  std::string error;
  ASSERT_TRUE(parse_dsp_hitl_status(kSpecStatus, &r, &error)) << error;
  EXPECT_TRUE(r.running);
  EXPECT_EQ(r.counters.hil_imu_received, 12453U);
  EXPECT_EQ(r.counters.imu_published, 12450U);
  EXPECT_EQ(r.counters.hil_mag_baro_received, 4980U);
  EXPECT_EQ(r.counters.mag_published, 4975U);
  EXPECT_EQ(r.counters.baro_published, 995U);
  EXPECT_TRUE(r.current.imu_received);
  EXPECT_FLOAT_EQ(r.current.accel_FRD_m_s2[2], -9.859F);
  EXPECT_FLOAT_EQ(r.current.gyro_FRD_rad_s[0], -0.006F);
}

TEST(DspHitlStatusParse, RoundTripsTheFormatterIncludingNoDataAndHugeCounters) {
  DspHitl d;
  DspHitlStatusReport r;
  std::string error;
  ASSERT_TRUE(parse_dsp_hitl_status(d.status_text(), &r, &error)) << error;
  EXPECT_FALSE(r.running);
  EXPECT_FALSE(r.current.imu_received);
  EXPECT_EQ(r.counters.baro_published, 0U);

  DspHitlCounters c = spec_counters();
  c.hil_imu_received = 5000000000ULL;
  ASSERT_TRUE(parse_dsp_hitl_status(dsp_hitl_status_text(true, c, spec_current()), &r, &error)) << error;
  EXPECT_EQ(r.counters.hil_imu_received, 5000000000ULL);
}

TEST(DspHitlStatusParse, ToleratesCarriageReturnsPrefixesAndExtraLines) {
  // What a shell may add: CRLF line ends, a log prefix per line, a trailing prompt.
  std::string text = "INFO  [qshell] Send cmd: 'dsp_hitl status'\r\n";
  std::string spec = kSpecStatus;
  for (std::size_t at = 0; (at = spec.find('\n', at)) != std::string::npos; at += 2) spec.replace(at, 1, "\r\n");
  text += spec + "INFO  [qshell] qshell return value timestamp: 1234, local time: 1240\r\npxh> ";
  DspHitlStatusReport r;
  std::string error;
  ASSERT_TRUE(parse_dsp_hitl_status(text, &r, &error)) << error;
  EXPECT_EQ(r.counters.mag_published, 4975U);
  EXPECT_TRUE(r.running);
}

TEST(DspHitlStatusParse, NamesWhatIsMissingOrMalformed) {
  DspHitlStatusReport r;
  std::string error;
  EXPECT_FALSE(parse_dsp_hitl_status("nsh: dsp_hitl: command not found\n", &r, &error));
  EXPECT_NE(error.find("Running"), std::string::npos) << error;

  std::string truncated = kSpecStatus;
  truncated.resize(truncated.find("  BARO updates"));
  EXPECT_FALSE(parse_dsp_hitl_status(truncated, &r, &error));
  EXPECT_NE(error.find("BARO updates published"), std::string::npos) << error;

  std::string garbled = kSpecStatus;
  garbled.replace(garbled.find("12450"), 5, "12x50");
  EXPECT_FALSE(parse_dsp_hitl_status(garbled, &r, &error));
  EXPECT_NE(error.find("IMU updates published"), std::string::npos) << error;

  std::string negative = kSpecStatus;
  negative.replace(negative.find("995"), 3, "-1");
  EXPECT_FALSE(parse_dsp_hitl_status(negative, &r, &error));

  std::string overflow = kSpecStatus;
  overflow.replace(overflow.find("995"), 3, "99999999999999999999999");
  EXPECT_FALSE(parse_dsp_hitl_status(overflow, &r, &error));

  std::string bad_vector = kSpecStatus;
  bad_vector.replace(bad_vector.find("-0.257, 0.151"), 13, "-0.257; 0.151");
  EXPECT_FALSE(parse_dsp_hitl_status(bad_vector, &r, &error));
  EXPECT_NE(error.find("accel"), std::string::npos) << error;

  EXPECT_FALSE(parse_dsp_hitl_status("", &r, &error));
}

}  // namespace
}  // namespace hitl::target
