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
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "base/mavlink/frame_parser.h"
#include "base/mavlink/message_set.h"
#include "engine/mavlink/field_format.h"
#include "tests/base/mavlink/node_mavlink_cases.h"

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
using namespace conformance;

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
