// Byte-for-byte conformance of hitl's MAVLink v2 codec against the independent npm
// package node-mavlink (pinned in tests/base/mavlink/node/package.json and installed by
// the CTest fixture node_mavlink_install; see node_mavlink.cmake).
//
// For every message of msg::All and several value patterns, hitl encodes a frame; one
// node process (node/check.js) decodes all of them with node-mavlink and encodes the same
// values itself. Then, per case:
//   - node-mavlink's frame must equal hitl's frame byte for byte;
//   - the values node-mavlink decoded from hitl's frame must equal the values hitl encoded
//     (compared as wire bytes, so floats are bit-exact float32/float64);
//   - hitl's FrameParser must decode node-mavlink's frame to the same values;
//   - signed frames: hitl verifies node-mavlink's signature and node-mavlink hitl's.
//
// Known node-mavlink deviation (checked exactly, not skipped): see kAllZeroDeviation.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <array>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include <unistd.h>

#include "base/mavlink/crc.h"
#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/message_set.h"
#include "base/mavlink/messages.h"
#include "base/mavlink/typed_codec.h"
#include "engine/mavlink/field_format.h"

#ifndef HITL_NODE_EXECUTABLE
#define HITL_NODE_EXECUTABLE ""
#endif
#ifndef HITL_NODE_MAVLINK_DIR
#define HITL_NODE_MAVLINK_DIR ""
#endif
#ifndef HITL_NODE_CHECK_JS
#define HITL_NODE_CHECK_JS ""
#endif

namespace hitl::mavlink {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr uint8_t kSysid = 7;
constexpr uint8_t kCompid = 200;
constexpr uint8_t kLinkId = 3;
constexpr uint64_t kSignEpochMs = 1420070400000ULL;      // 2015-01-01T00:00:00Z
constexpr uint64_t kSignBaseMs = 1700000000000ULL;       // a fixed signing time (ms since Unix epoch)
constexpr SigningKey kKey = {0x9a, 0x1c, 0x44, 0x07, 0xe2, 0x5d, 0x80, 0x31, 0x6f, 0xc4, 0x12, 0xab, 0x03, 0x99, 0x58, 0x21,
                             0xde, 0x70, 0x0b, 0x6a, 0x35, 0xf1, 0x8c, 0x27, 0x41, 0xb9, 0x5e, 0x02, 0xcd, 0x13, 0x76, 0xe8};

// Known deviation of node-mavlink 2.3.0, checked exactly below rather than skipped:
// MavLinkProtocolV2.calculateTruncatedPayloadLength (node_modules/node-mavlink/dist/lib/mavlink.js)
// strips every trailing zero, so a message whose payload is all zeros goes out with LEN 0.
// https://mavlink.io/en/guide/serialization.html (Empty-Byte Payload Truncation) says "The first
// byte of the payload is never truncated, even if the payload consists entirely of zeros", and
// c_library_v2 (_mav_trim_payload) keeps one byte; hitl does the same. So for all-zero messages the
// test expects node's frame to be hitl's frame with LEN 0, no payload byte and the checksum
// recomputed, and still requires both sides to decode each other's frame.
// Known gap of node-mavlink 2.3.0 / mavlink-mappings 1.0.21-20250824-1, checked exactly below:
// EVENT (#410, common.xml) is missing. No class in node_modules/mavlink-mappings/dist/lib/*.js has
// MSG_ID = 410 (the messages around it stop at SUPPORTED_TUNES #401 and resume at AVAILABLE_MODES
// #435, also lacking CURRENT_EVENT_SEQUENCE #411, REQUEST_EVENT #412, RESPONSE_EVENT_ERROR #413),
// and MSG_ID_MAGIC_NUMBER in magic-numbers.js has no key 410, so node-mavlink's splitter drops such
// frames as unknown. For these messages the test requires exactly that (no class, no CRC_EXTRA,
// hitl's frame dropped); a node-mavlink that learns the message makes the test fail so the
// exception can be removed. Their bytes are checked against the XML by the XML conformance test.
const std::set<std::string> kMissingInNodeMavlink = {"EVENT"};

constexpr const char* kAllZeroDeviation =
    "node-mavlink 2.3.0 truncates an all-zero v2 payload to LEN 0 (spec and hitl keep 1 byte)";

// ---------------------------------------------------------------- deterministic values

struct Rng {
  uint64_t state;
  uint64_t next() {  // splitmix64
    uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
};

enum class Fill {
  Random,        ///< full-range random bits (finite floats incl. subnormals and -0), strings with a NUL
  Extremes,      ///< min/max/0/-1 integers, +-max/+-denorm/-0 floats, strings filling the whole array
  TrailingZero,  ///< random, but the second half of the fields (wire order) zero: v2 truncation
  AllZero,       ///< every field zero (see kAllZeroDeviation)
};

const char* fill_name(Fill fill) {
  switch (fill) {
    case Fill::Random: return "random";
    case Fill::Extremes: return "extremes";
    case Fill::TrailingZero: return "trailing-zero";
    case Fill::AllZero: return "all-zero";
  }
  return "?";
}

template <class T>
T random_element(Rng& rng, Fill fill, std::size_t k) {
  if constexpr (std::is_same_v<T, float> || std::is_same_v<T, double>) {
    using Bits = std::conditional_t<std::is_same_v<T, float>, uint32_t, uint64_t>;
    if (fill == Fill::Extremes) {
      constexpr T kValues[] = {std::numeric_limits<T>::max(),        -std::numeric_limits<T>::max(),
                               std::numeric_limits<T>::denorm_min(), -std::numeric_limits<T>::denorm_min(),
                               T(-0.0),                              std::numeric_limits<T>::min(),
                               T(1.0),                               T(-1.0)};
      return kValues[k % std::size(kValues)];
    }
    constexpr int kMantissa = std::numeric_limits<T>::digits - 1;
    constexpr Bits kExpMask = ((Bits{1} << (sizeof(T) * 8 - 1 - kMantissa)) - 1) << kMantissa;
    Bits bits = static_cast<Bits>(rng.next());
    if ((bits & kExpMask) == kExpMask) bits &= ~(Bits{1} << (sizeof(T) * 8 - 2));  // Inf/NaN -> finite
    return std::bit_cast<T>(bits);
  } else {
    if (fill == Fill::Extremes) {
      const T kValues[] = {std::numeric_limits<T>::max(), std::numeric_limits<T>::min(), T(1),
                           static_cast<T>(std::numeric_limits<T>::max() - 1), static_cast<T>(-1)};
      return kValues[k % std::size(kValues)];
    }
    return static_cast<T>(rng.next());
  }
}

template <class T>
void fill_value(T& value, Rng& rng, Fill fill, std::size_t k) {
  value = random_element<T>(rng, fill, k);
}

template <class T, std::size_t N>
void fill_value(std::array<T, N>& values, Rng& rng, Fill fill, std::size_t k) {
  if constexpr (std::is_same_v<T, char>) {
    values.fill('\0');
    // Random: a string of 0..N-1 bytes (1..255) and its NUL. Extremes: all N bytes used, no NUL.
    const std::size_t len = fill == Fill::Extremes ? N : static_cast<std::size_t>(rng.next() % N);
    for (std::size_t i = 0; i < len; ++i) {
      const uint8_t byte = fill == Fill::Extremes ? static_cast<uint8_t>(0x20 + (k + i) % 95)
                                                  : static_cast<uint8_t>(1 + rng.next() % 255);
      values[i] = static_cast<char>(byte);
    }
  } else {
    for (std::size_t i = 0; i < N; ++i) values[i] = random_element<T>(rng, fill, k + i);
  }
}

template <class M>
M make_message(Fill fill, uint64_t seed) {
  M m{};
  if (fill == Fill::AllZero) return m;
  Rng rng{seed};
  constexpr std::size_t kFields = std::tuple_size_v<decltype(M::fields())>;
  std::size_t index = 0;
  std::apply(
      [&](const auto&... field) {
        auto one = [&](const auto& f) {
          const std::size_t i = index++;
          if (fill == Fill::TrailingZero && i >= (kFields + 1) / 2) return;  // stays zero
          fill_value(m.*(f.member), rng, fill, i);
        };
        (one(field), ...);
      },
      M::fields());
  return m;
}

// ---------------------------------------------------------------- helpers

std::string to_hex(std::span<const uint8_t> bytes) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out;
  out.reserve(bytes.size() * 2);
  for (uint8_t b : bytes) {
    out += kDigits[b >> 4];
    out += kDigits[b & 0x0F];
  }
  return out;
}

std::vector<uint8_t> from_hex(const std::string& hex) {
  std::vector<uint8_t> out;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2) out.push_back(static_cast<uint8_t>(std::stoul(hex.substr(i, 2), nullptr, 16)));
  return out;
}

/// Where two byte strings first differ, named in frame terms.
std::string describe_difference(const std::vector<uint8_t>& got, const std::vector<uint8_t>& want, const MessageDesc& desc) {
  std::size_t i = 0;
  while (i < got.size() && i < want.size() && got[i] == want[i]) ++i;
  std::ostringstream os;
  os << "first difference at byte " << i << " (lengths " << got.size() << " vs " << want.size() << ")";
  if (i < kHeaderLenV2) {
    static constexpr const char* kNames[] = {"STX", "LEN", "incompat", "compat", "seq", "sysid", "compid", "msgid", "msgid", "msgid"};
    os << ": header " << kNames[i];
  } else if (want.size() >= kHeaderLenV2 + kChecksumLen && i >= want.size() - kChecksumLen) {
    os << ": checksum";
  } else {
    const std::size_t off = i - kHeaderLenV2;
    for (const auto& f : desc.fields) {
      if (off >= f.offset && off < f.offset + f.wire_size()) os << ": payload field " << f.name;
    }
  }
  return os.str();
}

/// One field's wire bytes -> text via field_format (for readable failure messages).
std::string field_text(const FieldDesc& field, const std::vector<uint8_t>& bytes) {
  std::array<uint8_t, kMaxPayloadLen + 8> payload{};
  for (std::size_t i = 0; i < bytes.size() && field.offset + i < payload.size(); ++i) payload[field.offset + i] = bytes[i];
  return format_field(field, payload.data());
}

std::vector<Frame> parse_all(std::span<const uint8_t> bytes, const MessageSet& set, ParserOptions options, ParserStats* stats = nullptr) {
  FrameParser parser(set, std::move(options));
  std::vector<Frame> frames;
  parser.parse_datagram(bytes, [&](const Frame& f) { frames.push_back(f); });
  if (stats) *stats = parser.stats();
  return frames;
}

// ---------------------------------------------------------------- cases

struct Case {
  std::string name;      ///< "HIL_SENSOR/random"
  std::string msgname;
  Fill fill = Fill::Random;
  uint8_t seq = 0;
  std::vector<uint8_t> hitl_frame;
  std::vector<uint8_t> hitl_signed_frame;
  std::array<uint8_t, kMaxPayloadLen> payload{};  ///< untruncated payload of the values
  const MessageDesc* desc = nullptr;
  uint64_t sign_ms = 0;  ///< node signs at this time when non-zero
  /// hitl's decode of node-mavlink's frame, re-encoded untruncated (filled by the checker).
  std::function<std::array<uint8_t, kMaxPayloadLen>(const Frame&)> reencode;
};

template <class M>
void add_cases(std::vector<Case>& cases, json& jobs, FrameEncoder& encoder, FrameEncoder& signer, const MessageSet& set) {
  const MessageDesc* desc = set.find(M::kId);
  ASSERT_NE(desc, nullptr) << M::kName;
  for (Fill fill : {Fill::Random, Fill::Extremes, Fill::TrailingZero, Fill::AllZero}) {
    Case c;
    c.msgname = std::string(M::kName);
    c.name = c.msgname + "/" + fill_name(fill);
    c.fill = fill;
    c.desc = desc;
    const M message = make_message<M>(fill, (uint64_t{M::kId} << 8) ^ static_cast<uint64_t>(fill) ^ 0x5EED0000ULL);
    encode_payload(message, c.payload.data());
    c.seq = encoder.next_seq();
    FrameBuffer buf{};
    c.hitl_frame.assign(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(encoder.encode(message, buf)));
    c.reencode = [](const Frame& f) {
      std::array<uint8_t, kMaxPayloadLen> out{};
      encode_payload(f.as<M>(), out.data());
      return out;
    };

    json job = {{"name", c.name}, {"msgname", c.msgname}, {"msgid", M::kId}, {"crc_extra", M::kCrcExtra},
                {"max_length", M::kMaxLength}, {"seq", c.seq}, {"sysid", kSysid}, {"compid", kCompid},
                {"hitl_frame", to_hex(c.hitl_frame)}};
    json fields = json::array();
    for (const auto& f : desc->fields) {
      fields.push_back({{"name", f.name}, {"type", std::string(to_string(f.type))}, {"length", f.array_length},
                        {"offset", f.offset}, {"extension", f.extension},
                        {"hex", to_hex(std::span<const uint8_t>(c.payload.data() + f.offset, f.wire_size()))}});
    }
    job["fields"] = std::move(fields);
    if (fill == Fill::Random) {
      c.sign_ms = kSignBaseMs + M::kId;
      const std::size_t n = signer.encode(message, buf);
      c.hitl_signed_frame.assign(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n));
      job["hitl_signed_frame"] = to_hex(c.hitl_signed_frame);
      job["sign"] = {{"key", to_hex(kKey)}, {"link_id", kLinkId}, {"timestamp_ms", c.sign_ms}};
    }
    jobs.push_back(std::move(job));
    cases.push_back(std::move(c));
  }
}

template <class... Ms>
void add_all_cases(std::vector<Case>& cases, json& jobs, FrameEncoder& encoder, FrameEncoder& signer, const MessageSet& set,
                   TypeList<Ms...>) {
  (add_cases<Ms>(cases, jobs, encoder, signer, set), ...);
}

/// The frame node-mavlink is expected to send for an all-zero message (kAllZeroDeviation).
std::vector<uint8_t> expected_node_all_zero(const std::vector<uint8_t>& hitl_frame, const MessageDesc& desc) {
  std::vector<uint8_t> out(hitl_frame.begin(), hitl_frame.begin() + kHeaderLenV2);
  out[1] = 0;
  uint16_t crc = crc_x25(std::span<const uint8_t>(out.data() + 1, kHeaderLenV2 - 1));
  crc = crc_accumulate(desc.crc_extra, crc);
  out.push_back(static_cast<uint8_t>(crc));
  out.push_back(static_cast<uint8_t>(crc >> 8));
  return out;
}

// ---------------------------------------------------------------- node

struct NodeRun {
  json out;
  std::string error;
};

NodeRun run_node(const json& jobs) {
  NodeRun run;
  const std::string node = HITL_NODE_EXECUTABLE;
  const fs::path modules = fs::path(HITL_NODE_MAVLINK_DIR) / "node_modules";
  if (node.empty() || !fs::exists(node)) {
    run.error = "node (Node.js >= 18) was not found when CMake configured the build; install Node.js and npm and reconfigure";
    return run;
  }
  if (!fs::exists(modules / "node-mavlink" / "package.json")) {
    run.error = "node-mavlink is not installed in " + modules.string() +
                "; run the fixture test first: ctest -R node_mavlink_install (needs npm and network access to the npm registry)";
    return run;
  }
  const fs::path dir = fs::temp_directory_path() / ("hitl-node-mavlink-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path job_path = dir / "job.json", out_path = dir / "out.json", err_path = dir / "stderr.txt";
  std::ofstream(job_path) << json{{"cases", jobs}}.dump();
  const std::string cmd = "NODE_PATH='" + modules.string() + "' '" + node + "' '" + HITL_NODE_CHECK_JS + "' '" + job_path.string() +
                          "' '" + out_path.string() + "' 2> '" + err_path.string() + "'";
  const int rc = std::system(cmd.c_str());
  std::ifstream err_in(err_path);
  const std::string err((std::istreambuf_iterator<char>(err_in)), std::istreambuf_iterator<char>());
  if (rc != 0) {
    run.error = "check.js failed (status " + std::to_string(rc) + "): " + err;
  } else {
    std::ifstream in(out_path);
    run.out = json::parse(in, nullptr, false);
    if (run.out.is_discarded()) run.error = "check.js wrote invalid JSON";
  }
  fs::remove_all(dir);
  return run;
}

// ---------------------------------------------------------------- the test

TEST(NodeMavlinkConformance, EveryCompiledMessageByteForByte) {
  const MessageSet set = MessageSet::compiled();
  FrameEncoder encoder(kSysid, kCompid);
  FrameEncoder signer(kSysid, kCompid);
  signer.set_signing(kKey, kLinkId);
  std::vector<Case> cases;
  json jobs = json::array();
  add_all_cases(cases, jobs, encoder, signer, set, msg::All{});
  ASSERT_EQ(set.size(), cases.size() / 4);

  const NodeRun run = run_node(jobs);
  ASSERT_TRUE(run.error.empty()) << run.error;
  const json& results = run.out.at("cases");
  ASSERT_EQ(results.size(), cases.size());
  std::cout << "[ node     ] node-mavlink " << run.out.value("node_mavlink_version", "?") << ", mavlink-mappings "
            << run.out.value("mavlink_mappings_version", "?") << ", node " << run.out.value("node_version", "?") << "\n";

  std::map<std::string, std::vector<std::string>> problems;  // message -> what differed
  std::map<std::string, int> deviations;
  std::set<std::string> missing;  // kMissingInNodeMavlink, confirmed
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    const json& r = results[i];
    const MessageDesc& desc = *c.desc;
    auto& bad = problems[c.msgname];
    auto fail = [&](const std::string& what) { bad.push_back(std::string(fill_name(c.fill)) + ": " + what); };
    ASSERT_EQ(r.at("name"), c.name);
    for (const auto& e : r.at("errors")) fail(e.get<std::string>());
    if (kMissingInNodeMavlink.count(c.msgname)) {
      if (!r.value("missing_class", false)) {
        fail("node-mavlink now has this message: remove it from kMissingInNodeMavlink");
      } else if (r.value("magic_known", true) || !r.contains("decoded") || r.at("decoded").at("frames") != 0) {
        fail("node-mavlink lacks the class but not as documented: " + r.dump());
      } else {
        missing.insert(c.msgname);
      }
      continue;
    }
    if (r.value("missing_class", false)) {
      fail("node-mavlink has no class for this message");
      continue;
    }

    // 1. node-mavlink decoded hitl's frame to the values hitl encoded.
    if (!r.contains("decoded")) {
      fail("node-mavlink did not decode hitl's frame");
    } else {
      const json& d = r.at("decoded");
      if (d.at("frames") != 1 || d.at("crc_errors") != 0) {
        fail("node-mavlink accepted " + d.at("frames").dump() + " frames of hitl's 1 (CRC errors: " + d.at("crc_errors").dump() + ")");
      } else {
        const json& h = d.at("header");
        if (h.at("msgid") != desc.id || h.at("seq") != c.seq || h.at("sysid") != kSysid || h.at("compid") != kCompid)
          fail("node-mavlink read header " + h.dump());
        for (const auto& f : desc.fields) {
          const std::vector<uint8_t> want(c.payload.begin() + f.offset, c.payload.begin() + f.offset + f.wire_size());
          if (d.at("field_errors").contains(f.name)) {
            fail("node decoded " + f.name + " as a bad value: " + d.at("field_errors").at(f.name).get<std::string>());
          } else if (!d.at("fields").contains(f.name)) {
            fail("node did not decode " + f.name);
          } else if (const auto got = from_hex(d.at("fields").at(f.name)); got != want) {
            fail("node decoded " + f.name + " = " + field_text(f, got) + ", hitl encoded " + field_text(f, want));
          }
        }
      }
      if (c.fill == Fill::Random) {
        const json& s = r.at("decoded_signed");
        if (s.at("frames") != 1 || !s.at("header").at("signed").get<bool>() || !s.value("signature_ok", false))
          fail("node-mavlink did not verify hitl's signed frame: " + s.dump());
      }
    }

    // 2. node-mavlink's frame equals hitl's byte for byte.
    if (!r.contains("node_frame")) {
      fail("node-mavlink produced no frame");
      continue;
    }
    const std::vector<uint8_t> node_frame = from_hex(r.at("node_frame"));
    if (c.fill == Fill::AllZero) {
      const auto expected = expected_node_all_zero(c.hitl_frame, desc);
      if (node_frame == expected) {
        ++deviations[c.msgname];
      } else if (node_frame != c.hitl_frame) {
        fail("all-zero frame is neither hitl's nor the documented deviation: " + describe_difference(node_frame, c.hitl_frame, desc) +
             "\n  node " + to_hex(node_frame) + "\n  hitl " + to_hex(c.hitl_frame));
      }
    } else if (node_frame != c.hitl_frame) {
      fail("frames differ, " + describe_difference(node_frame, c.hitl_frame, desc) + "\n  node " + to_hex(node_frame) +
           "\n  hitl " + to_hex(c.hitl_frame));
    }

    // 3. hitl's parser decodes node-mavlink's frame to the same values.
    ParserStats stats;
    const auto frames = parse_all(node_frame, set, {}, &stats);
    if (frames.size() != 1 || frames[0].desc == nullptr) {
      fail("hitl parsed " + std::to_string(frames.size()) + " frames from node's frame (crc errors " + std::to_string(stats.crc_errors) + ")");
    } else {
      const Frame& f = frames[0];
      if (f.msgid != desc.id || f.seq != c.seq || f.sysid != kSysid || f.compid != kCompid) fail("hitl read node's header wrongly");
      const auto decoded = c.reencode(f);
      for (const auto& fd : desc.fields) {
        const std::vector<uint8_t> got(decoded.begin() + fd.offset, decoded.begin() + fd.offset + fd.wire_size());
        const std::vector<uint8_t> want(c.payload.begin() + fd.offset, c.payload.begin() + fd.offset + fd.wire_size());
        if (got != want) fail("hitl decoded node's " + fd.name + " = " + field_text(fd, got) + ", expected " + field_text(fd, want));
      }
    }

    // 4. hitl verifies node-mavlink's signature.
    if (c.fill == Fill::Random) {
      ParserOptions options;
      options.signing_key = kKey;
      options.accept_unsigned = false;
      const auto signed_frames = parse_all(from_hex(r.at("node_signed_frame")), set, options, &stats);
      if (signed_frames.size() != 1 || !signed_frames[0].is_signed()) {
        fail("hitl did not accept node's signed frame (signature errors " + std::to_string(stats.signature_errors) + ")");
      } else {
        const Frame& f = signed_frames[0];
        if (f.signature_link_id() != kLinkId || f.signature_timestamp() != (c.sign_ms - kSignEpochMs) * 100)
          fail("node's signature link/timestamp read as " + std::to_string(f.signature_link_id()) + "/" +
               std::to_string(f.signature_timestamp()));
        if (c.reencode(f) != c.payload) fail("hitl decoded node's signed frame to other values");
      }
    }
  }

  // Per-message summary, then one failure per message that differed.
  std::cout << "[ node     ] " << cases.size() << " cases, " << set.size() << " messages\n";
  for (const auto& [name, list] : problems) {
    const std::string note = deviations.count(name) ? "  (all-zero case: " + std::string(kAllZeroDeviation) + ")" : "";
    if (list.empty() && missing.count(name)) {
      std::cout << "[ node     ] n/a  " << name << "  (not in node-mavlink; see kMissingInNodeMavlink)\n";
      continue;
    }
    std::cout << "[ node     ] " << (list.empty() ? "ok   " : "FAIL ") << name << (list.empty() ? note : "") << "\n";
    if (!list.empty()) {
      std::string text;
      for (const auto& p : list) text += "\n    " + p;
      ADD_FAILURE() << name << " differs from node-mavlink:" << text;
    }
  }
}

}  // namespace
}  // namespace hitl::mavlink
