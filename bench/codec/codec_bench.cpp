// MAVLink codec throughput. items_per_second in the output is frames per second.
//
//   codec_bench                       all benchmarks
//   codec_bench --benchmark_filter=HilSensor
//
// Goal (issue): >= 5 million HIL_SENSOR frames/s parsed, checked and decoded on one core.
#include <benchmark/benchmark.h>

#include <array>
#include <cstdint>
#include <vector>

#include "base/mavlink/crc.h"
#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/message_set.h"
#include "base/mavlink/messages.h"

namespace {

using namespace hitl::mavlink;
using Bytes = std::vector<uint8_t>;

constexpr std::size_t kFrames = 1024;  // distinct frames cycled through, so branch predictors see real data

msg::HilSensor hil_sensor(uint32_t i) {
  msg::HilSensor m;
  m.time_usec = 1'000'000 + uint64_t{i} * 4000;
  m.xacc = 0.01f * static_cast<float>(i % 17), m.yacc = -0.02f, m.zacc = -9.81f;
  m.xgyro = 0.001f * static_cast<float>(i % 13), m.ygyro = 0.002f, m.zgyro = -0.003f;
  m.xmag = 0.21f, m.ymag = 0.01f, m.zmag = 0.42f;
  m.abs_pressure = 1013.25f - 0.001f * static_cast<float>(i), m.diff_pressure = 0.1f, m.pressure_alt = 10.0f;
  m.temperature = 21.5f, m.fields_updated = 0x1FFF, m.id = 0;
  return m;
}

template <class M>
Bytes encode(FrameEncoder& enc, const M& m) {
  FrameBuffer buf{};
  const std::size_t n = enc.encode(m, buf);
  return Bytes(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n));
}

std::vector<Bytes> hil_sensor_frames() {
  FrameEncoder enc(1, 1);
  std::vector<Bytes> out;
  for (uint32_t i = 0; i < kFrames; ++i) out.push_back(encode(enc, hil_sensor(i)));
  return out;
}

Bytes concat(const std::vector<Bytes>& frames) {
  Bytes out;
  for (const auto& f : frames) out.insert(out.end(), f.begin(), f.end());
  return out;
}

/// What a HIL receiver does with a frame: decode it into the typed struct.
struct Sink {
  uint64_t frames = 0;
  float acc = 0;
  void operator()(const Frame& f) {
    ++frames;
    switch (f.msgid) {
      case msg::HilSensor::kId: acc += f.as<msg::HilSensor>().zacc; break;
      case msg::HilGps::kId: acc += static_cast<float>(f.as<msg::HilGps>().lat); break;
      case msg::Odometry::kId: acc += f.as<msg::Odometry>().x; break;
      case msg::Heartbeat::kId: acc += static_cast<float>(f.as<msg::Heartbeat>().custom_mode); break;
      case msg::Attitude::kId: acc += f.as<msg::Attitude>().roll; break;
      case msg::Statustext::kId: acc += static_cast<float>(f.as<msg::Statustext>().text[0]); break;
      case msg::HilStateQuaternion::kId: acc += f.as<msg::HilStateQuaternion>().rollspeed; break;
      case msg::HilActuatorControls::kId: acc += f.as<msg::HilActuatorControls>().controls[0]; break;
      default: break;
    }
  }
};

void BM_ParseDatagram_HilSensor(benchmark::State& state) {
  const MessageSet set = MessageSet::compiled();
  const auto frames = hil_sensor_frames();
  FrameParser parser(set);
  Sink sink;
  const FrameParser::FrameHandler handler = [&](const Frame& f) { sink(f); };
  std::size_t i = 0;
  for (auto _ : state) {
    parser.parse_datagram(frames[i], handler);
    i = (i + 1) % kFrames;
  }
  benchmark::DoNotOptimize(sink.acc);
  if (sink.frames != static_cast<uint64_t>(state.iterations())) state.SkipWithError("frames lost");
  state.SetItemsProcessed(static_cast<int64_t>(sink.frames));
  state.SetBytesProcessed(static_cast<int64_t>(parser.stats().bytes));
}
BENCHMARK(BM_ParseDatagram_HilSensor);

void BM_ParseDatagram_HilSensor_Signed(benchmark::State& state) {
  const MessageSet set = MessageSet::compiled();
  SigningKey key{};
  key.fill(0x5A);
  std::vector<Bytes> frames;
  FrameEncoder enc(1, 1);
  enc.set_signing(key, 1);
  for (uint32_t i = 0; i < kFrames; ++i) frames.push_back(encode(enc, hil_sensor(i)));
  Sink sink;
  const FrameParser::FrameHandler handler = [&](const Frame& f) { sink(f); };
  uint64_t expected = 0;
  for (auto _ : state) {
    state.PauseTiming();  // a fresh parser per pass over the frames: timestamps must advance
    FrameParser parser(set, ParserOptions{key, false});
    state.ResumeTiming();
    for (const auto& f : frames) parser.parse_datagram(f, handler);
    expected += kFrames;
  }
  benchmark::DoNotOptimize(sink.acc);
  if (sink.frames != expected) state.SkipWithError("frames lost");
  state.SetItemsProcessed(static_cast<int64_t>(sink.frames));
}
BENCHMARK(BM_ParseDatagram_HilSensor_Signed)->Unit(benchmark::kMicrosecond);

void feed_stream(benchmark::State& state, const Bytes& stream, std::size_t frames_per_stream) {
  const MessageSet set = MessageSet::compiled();
  const std::size_t chunk = static_cast<std::size_t>(state.range(0));
  FrameParser parser(set);
  Sink sink;
  const FrameParser::FrameHandler handler = [&](const Frame& f) { sink(f); };
  for (auto _ : state) {
    for (std::size_t pos = 0; pos < stream.size(); pos += chunk)
      parser.feed(std::span<const uint8_t>(stream).subspan(pos, std::min(chunk, stream.size() - pos)), handler);
  }
  benchmark::DoNotOptimize(sink.acc);
  if (sink.frames != frames_per_stream * static_cast<uint64_t>(state.iterations())) state.SkipWithError("frames lost");
  state.SetItemsProcessed(static_cast<int64_t>(sink.frames));
  state.SetBytesProcessed(static_cast<int64_t>(parser.stats().bytes));
}

void BM_FeedStream_HilSensor(benchmark::State& state) {
  static const Bytes stream = concat(hil_sensor_frames());
  feed_stream(state, stream, kFrames);
}
// Chunk sizes: a serial read (64 B), a UDP/TCP read (1500 B), the whole 1024-frame stream.
BENCHMARK(BM_FeedStream_HilSensor)->Arg(64)->Arg(1500)->Arg(1 << 20)->Unit(benchmark::kMicrosecond);

Bytes mixed_stream(std::size_t& frames) {
  FrameEncoder enc(1, 1);
  std::vector<Bytes> out;
  for (uint32_t i = 0; i < kFrames; ++i) {
    out.push_back(encode(enc, hil_sensor(i)));  // 250 Hz sensors dominate a HIL link
    if (i % 5 == 0) {
      msg::HilGps g;
      g.time_usec = i, g.lat = 473977418 + static_cast<int32_t>(i), g.lon = 85455939, g.alt = 488000, g.fix_type = 3;
      out.push_back(encode(enc, g));
    }
    if (i % 4 == 0) {
      msg::Odometry o;
      o.time_usec = i, o.x = static_cast<float>(i), o.q = {1, 0, 0, 0}, o.frame_id = 1, o.child_frame_id = 8;
      out.push_back(encode(enc, o));
    }
    if (i % 4 == 2) {
      msg::Attitude a;
      a.time_boot_ms = i, a.roll = 0.1f, a.pitch = 0.2f, a.yaw = 0.3f;
      out.push_back(encode(enc, a));
    }
    if (i % 8 == 1) {
      msg::HilActuatorControls c;
      c.time_usec = i, c.controls = {0.5f, 0.5f, 0.5f, 0.5f}, c.mode = 0x81;
      out.push_back(encode(enc, c));
    }
    if (i % 250 == 0) {
      msg::Heartbeat h;
      h.type = 2, h.autopilot = 12, h.base_mode = 0x81, h.mavlink_version = 3;
      out.push_back(encode(enc, h));
    }
    if (i % 500 == 7) {
      msg::Statustext t;
      const char text[] = "[ekf2] mag fusion started";
      for (std::size_t k = 0; k + 1 < sizeof text; ++k) t.text[k] = text[k];
      t.severity = 6;
      out.push_back(encode(enc, t));
    }
  }
  frames = out.size();
  return concat(out);
}

void BM_FeedStream_Mixed(benchmark::State& state) {
  static std::size_t frames = 0;
  static const Bytes stream = mixed_stream(frames);
  feed_stream(state, stream, frames);
}
BENCHMARK(BM_FeedStream_Mixed)->Arg(1500)->Unit(benchmark::kMicrosecond);

void BM_Encode_HilSensor(benchmark::State& state) {
  FrameEncoder enc(1, 1);
  std::vector<msg::HilSensor> messages;
  for (uint32_t i = 0; i < kFrames; ++i) messages.push_back(hil_sensor(i));
  FrameBuffer buf{};
  std::size_t i = 0, bytes = 0;
  for (auto _ : state) {
    bytes += enc.encode(messages[i], buf);
    benchmark::DoNotOptimize(buf.data());
    i = (i + 1) % kFrames;
  }
  state.SetItemsProcessed(state.iterations());
  state.SetBytesProcessed(static_cast<int64_t>(bytes));
}
BENCHMARK(BM_Encode_HilSensor);

// For reference: the checksum alone over one HIL_SENSOR frame (9 header bytes + 65 payload + CRC_EXTRA).
void BM_Crc_HilSensor(benchmark::State& state) {
  const auto frames = hil_sensor_frames();
  std::size_t i = 0;
  for (auto _ : state) {
    const Bytes& f = frames[i];
    uint16_t crc = crc_x25(std::span<const uint8_t>(f.data() + 1, f.size() - 3));
    crc = crc_accumulate(msg::HilSensor::kCrcExtra, crc);
    benchmark::DoNotOptimize(crc);
    i = (i + 1) % kFrames;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Crc_HilSensor);

}  // namespace

BENCHMARK_MAIN();
