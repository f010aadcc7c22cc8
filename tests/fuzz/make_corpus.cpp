// Writes the seed corpus of frame_parser_fuzz (tests/fuzz/corpus/frame_parser): valid v1,
// v2, truncated v2 and signed frames of several messages, garbage, damaged frames and mixes.
// Deterministic: the same files on every run (signature timestamps are fixed).
//
//   frame_parser_make_corpus OUT_DIR
#include <array>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/messages.h"
#include "base/mavlink/signing.h"
#include "tests/fuzz/fuzz_key.h"

namespace {

using namespace hitl::mavlink;
using Bytes = std::vector<uint8_t>;

struct Lcg {
  uint32_t s = 12345;
  uint8_t next() {
    s = s * 1103515245U + 12345U;
    return static_cast<uint8_t>(s >> 16);
  }
};

template <class M>
Bytes frame(const M& m, Version version = Version::V2, uint8_t seq = 0) {
  FrameEncoder enc(1, 1, version);
  FrameBuffer buf{};
  std::size_t n = 0;
  for (int i = 0; i <= seq; ++i) n = enc.encode(m, buf);
  return Bytes(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n));
}

/// A signed v2 frame with a fixed timestamp (FrameEncoder signs with the current time).
template <class M>
Bytes signed_frame(const M& m, uint64_t timestamp, uint8_t link_id = 1) {
  FrameEncoder enc(1, 1);
  enc.set_signing(hitl::fuzz::kFuzzKey, link_id);
  FrameBuffer buf{};
  const std::size_t n = enc.encode(m, buf);
  const std::size_t signed_len = n - kSignatureLen;
  for (int i = 0; i < 6; ++i) buf[signed_len + 1 + i] = static_cast<uint8_t>(timestamp >> (8 * i));
  const auto sig = compute_signature(hitl::fuzz::kFuzzKey, std::span<const uint8_t>(buf.data(), signed_len), link_id, timestamp);
  for (int i = 0; i < 6; ++i) buf[signed_len + 7 + i] = sig[static_cast<std::size_t>(i)];
  return Bytes(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n));
}

Bytes cat(std::initializer_list<Bytes> parts) {
  Bytes out;
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

Bytes garbage(std::size_t n, uint32_t seed) {
  Lcg rng{seed};
  Bytes out(n);
  for (auto& b : out) b = rng.next();
  return out;
}

msg::HilSensor hil_sensor() {
  msg::HilSensor m;
  m.time_usec = 123456789;
  m.xacc = 0.1f, m.yacc = -0.2f, m.zacc = -9.81f;
  m.xgyro = 0.01f, m.ygyro = -0.02f, m.zgyro = 0.03f;
  m.xmag = 0.2f, m.ymag = 0.0f, m.zmag = 0.4f;
  m.abs_pressure = 1013.25f, m.diff_pressure = 0.5f, m.pressure_alt = 12.0f, m.temperature = 21.5f;
  m.fields_updated = 0x1FFF;
  m.id = 1;
  return m;
}

msg::Heartbeat heartbeat() {
  msg::Heartbeat m;
  m.type = 2, m.autopilot = 12, m.base_mode = 0x81, m.custom_mode = 0x04000000, m.system_status = 4, m.mavlink_version = 3;
  return m;
}

msg::HilGps hil_gps() {
  msg::HilGps m;
  m.time_usec = 987654321, m.lat = 473977418, m.lon = 85455939, m.alt = 488000;
  m.eph = 30, m.epv = 40, m.vel = 150, m.vn = 100, m.ve = -50, m.vd = 5, m.cog = 9000;
  m.fix_type = 3, m.satellites_visible = 12;
  return m;
}

msg::Odometry odometry() {
  msg::Odometry m;
  m.time_usec = 5000000, m.x = 1.0f, m.y = 2.0f, m.z = -3.0f, m.q = {1.0f, 0.0f, 0.0f, 0.0f};
  m.vx = 0.5f, m.frame_id = 1, m.child_frame_id = 8, m.quality = 100;
  return m;
}

msg::Statustext statustext(const std::string& text) {
  msg::Statustext m;
  m.severity = 6;
  for (std::size_t i = 0; i < text.size() && i < m.text.size(); ++i) m.text[i] = text[i];
  return m;
}

msg::Attitude attitude() {
  msg::Attitude m;
  m.time_boot_ms = 1000, m.roll = 0.1f, m.pitch = -0.05f, m.yaw = 3.0f, m.rollspeed = 0.01f;
  return m;
}

msg::ParamValue param_value() {
  msg::ParamValue m;
  const std::string id = "MPC_XY_VEL_MAX";
  for (std::size_t i = 0; i < id.size(); ++i) m.param_id[i] = id[i];
  m.param_value = 12.0f, m.param_type = 9, m.param_count = 1000, m.param_index = 42;
  return m;
}

msg::SysStatus sys_status() {
  msg::SysStatus m;
  m.onboard_control_sensors_present = 0xFFFF, m.voltage_battery = 16000, m.battery_remaining = 80;
  m.onboard_control_sensors_health_extended = 1;  // an extension field: full length
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT_DIR\n", argv[0]);
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  std::filesystem::create_directories(dir);
  int written = 0;
  auto write = [&](const std::string& name, const Bytes& bytes) {
    std::ofstream(dir / name, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    ++written;
  };
  constexpr uint64_t kTs = 0x0000123456789AULL;

  // Valid v2 frames.
  write("v2_heartbeat", frame(heartbeat()));
  write("v2_hil_sensor", frame(hil_sensor()));
  write("v2_hil_gps", frame(hil_gps()));
  write("v2_odometry", frame(odometry()));
  write("v2_statustext", frame(statustext("PREFLIGHT FAIL: ACCEL SENSOR 0 MISSING")));
  write("v2_statustext_non_utf8", frame(statustext("\xff\xfe bad \xc3")));
  write("v2_attitude", frame(attitude()));
  write("v2_param_value", frame(param_value()));
  write("v2_sys_status_ext", frame(sys_status()));
  {
    msg::CommandLong m;
    m.command = 511, m.param1 = 107, m.param2 = 4000, m.target_system = 1, m.target_component = 1;
    write("v2_command_long", frame(m));
  }
  {
    msg::Timesync m;
    m.tc1 = 0, m.ts1 = -1234567890123LL;
    write("v2_timesync", frame(m));
  }
  {
    msg::Event m;
    m.id = 0x12345678, m.sequence = 7, m.log_levels = 0x64, m.arguments[0] = 1;
    write("v2_event", frame(m));
  }
  // Truncated v2 payloads (trailing zeros dropped) and the one-byte minimum.
  {
    msg::HilSensor m = hil_sensor();
    m.id = 0, m.fields_updated = 0, m.temperature = 0, m.pressure_alt = 0;
    write("v2_hil_sensor_truncated", frame(m));
    write("v2_all_zero_heartbeat", frame(msg::Heartbeat{}));
  }
  // v1 frames.
  write("v1_heartbeat", frame(heartbeat(), Version::V1));
  write("v1_attitude", frame(attitude(), Version::V1));
  write("v1_param_value", frame(param_value(), Version::V1));
  write("v1_hil_sensor", frame(hil_sensor(), Version::V1));
  // Signed v2 frames (key: fuzz_key.h).
  write("signed_hil_sensor", signed_frame(hil_sensor(), kTs));
  write("signed_heartbeat", signed_frame(heartbeat(), kTs + 1, 2));
  write("signed_statustext", signed_frame(statustext("signed"), kTs + 2));
  write("signed_replay", cat({signed_frame(heartbeat(), kTs), signed_frame(heartbeat(), kTs)}));
  {
    Bytes bad = signed_frame(hil_sensor(), kTs);
    bad.back() ^= 0x01;  // wrong signature
    write("signed_bad_signature", bad);
  }
  // Unknown id (checksum cannot be checked) and unknown incompat flags.
  {
    FrameEncoder enc(9, 9);
    FrameBuffer buf{};
    const Bytes payload = {1, 2, 3, 4, 5, 6, 7, 8};
    const std::size_t n = enc.encode_raw(0xABCDE, 77, payload, 8, buf);
    write("v2_unknown_id", Bytes(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n)));
    Bytes flags = frame(heartbeat());
    flags[2] = 0x02;
    write("v2_bad_incompat", flags);
  }
  // Damaged frames.
  {
    Bytes crc = frame(hil_sensor());
    crc[20] ^= 0x40;
    write("v2_bad_crc", crc);
    Bytes cut = frame(hil_sensor());
    cut.resize(cut.size() - 5);
    write("v2_cut_off", cut);
    Bytes len = frame(attitude());
    len[1] = 0xFF;
    write("v2_len_255", len);
    write("v1_cut_header", Bytes{0xFE, 0x09, 0x00});
    Bytes header = frame(heartbeat());
    header.resize(kHeaderLenV2);
    write("v2_header_only", header);
  }
  // Garbage.
  write("garbage_random", garbage(300, 1));
  write("garbage_stx_runs", Bytes(64, kStxV2));
  write("garbage_stx_mixed", cat({Bytes(20, kStxV1), Bytes(20, kStxV2), garbage(40, 2)}));
  write("empty_ish", Bytes{0x00});
  // Mixes: a HIL stream with garbage between frames, v1/v2/signed interleaved, a long stream.
  write("mix_hil_stream", cat({frame(heartbeat()), garbage(7, 3), frame(hil_sensor(), Version::V2, 1), frame(hil_gps()),
                               Bytes{0xFD, 0x01}, frame(odometry()), frame(statustext("hello"))}));
  write("mix_versions", cat({frame(heartbeat(), Version::V1), frame(attitude()), signed_frame(hil_sensor(), kTs),
                             frame(param_value(), Version::V1), garbage(5, 4), signed_frame(heartbeat(), kTs + 5)}));
  {
    Bytes partial = frame(hil_gps());
    partial.resize(20);
    write("mix_damaged", cat({frame(hil_sensor()), partial, frame(attitude()), garbage(33, 5), frame(sys_status())}));
  }
  {
    Bytes stream;
    for (int i = 0; i < 12; ++i) {
      msg::HilSensor m = hil_sensor();
      m.time_usec += static_cast<uint64_t>(i) * 4000;
      const Bytes f = frame(m, Version::V2, static_cast<uint8_t>(i));
      stream.insert(stream.end(), f.begin(), f.end());
      if (i % 6 == 5) {
        const Bytes g = frame(hil_gps(), Version::V2, static_cast<uint8_t>(i));
        stream.insert(stream.end(), g.begin(), g.end());
      }
    }
    write("mix_long_hil_sensor", stream);
  }
  std::printf("wrote %d files to %s\n", written, dir.c_str());
  return 0;
}
