// Streaming MAVLink frame parser: v1 and v2, resynchronising after garbage,
// checking the X.25 checksum with CRC_EXTRA, verifying signatures when given a key,
// and counting every kind of error. Every id of the official XML has its checksum checked, typed
// or not (message_check.h). A frame of an id neither the message set nor that XML knows cannot
// have its checksum checked: it is passed on raw (and counted) only when its framing is whole,
// as mavlink-router forwards such ids: it ends exactly at the end of a datagram or at the next
// start byte, and covers no frame whose checksum holds (a stream waits for the bytes to tell). Otherwise its start byte
// is garbage, so a stray start byte never swallows the frames after it.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <tuple>
#include <vector>

#include "base/mavlink/frame.h"
#include "base/mavlink/message_check.h"
#include "base/mavlink/message_set.h"
#include "base/mavlink/signing.h"

namespace hitl::mavlink {

struct ParserStats {
  uint64_t frames = 0;              ///< frames delivered (known and unknown ids)
  uint64_t v1_frames = 0;
  uint64_t signed_frames = 0;
  uint64_t bytes = 0;               ///< bytes fed
  uint64_t crc_errors = 0;          ///< complete frames of a known id (typed, --dialect or in the official XML) whose checksum did not match
  uint64_t parse_errors = 0;        ///< runs of bytes that were not part of any frame
  uint64_t garbage_bytes = 0;       ///< bytes in those runs
  uint64_t truncated = 0;           ///< frames cut off by the end of a datagram
  uint64_t untyped_frames = 0;      ///< frames delivered of an id of the official XML the message set has no description of (checksum checked)
  uint64_t unknown_ids = 0;         ///< frames delivered whose id neither the message set nor the official XML knows (framing whole)
  uint64_t unverified = 0;          ///< candidates whose checksum could not be checked (unknown id), delivered or not
  uint64_t unverified_dropped = 0;  ///< of those, the ones whose framing was not whole (their start byte counts as garbage)
  uint64_t bad_incompat_flags = 0;  ///< v2 frames with incompat flags hitl does not understand
  uint64_t signature_errors = 0;    ///< signed frames that failed verification or replayed a timestamp
  uint64_t unsigned_rejected = 0;   ///< unsigned frames refused because a key requires signing
};

struct ParserOptions {
  std::optional<SigningKey> signing_key;  ///< verify signatures with this key
  bool accept_unsigned = true;            ///< with a key: still accept unsigned frames
};

class FrameParser {
 public:
  using FrameHandler = std::function<void(const Frame&)>;

  explicit FrameParser(const MessageSet& messages, ParserOptions options = {});

  /// Feeds bytes of a stream (serial, TCP, tlog); a frame may span several calls.
  void feed(std::span<const uint8_t> bytes, const FrameHandler& on_frame);
  /// Parses one datagram: frames must lie wholly inside it; a partial frame at its end is counted as truncated.
  void parse_datagram(std::span<const uint8_t> datagram, const FrameHandler& on_frame);

  const ParserStats& stats() const { return stats_; }
  const MessageSet& messages() const { return *messages_; }

 private:
  /// Parses frames from `data`; returns how many bytes were consumed. With `final`,
  /// an incomplete frame is skipped rather than waited for.
  std::size_t process(std::span<const uint8_t> data, bool final, const FrameHandler& on_frame);
  enum class Candidate { Frame, NeedMore, Reject, SkipWhole };
  Candidate try_frame(std::span<const uint8_t> data, bool final, std::size_t& frame_len);
  enum class Check { No, Yes, Unknown };  ///< Unknown: a stream needs more bytes to tell
  static bool checksum_matches(std::span<const uint8_t> d, std::size_t header_len, std::size_t len, uint8_t crc_extra);
  /// The message set's CRC_EXTRA for the id, else the official XML's (message_check.h); none for an unknown id.
  static std::optional<uint8_t> crc_extra_of(uint32_t msgid, const MessageDesc* desc);
  /// Whether a complete frame of a known id with a good checksum starts at d[0].
  Check checked_frame_at(std::span<const uint8_t> d) const;
  /// Whether the unknown-id candidate d[0, frame_len) is framed whole (see the file comment).
  Check framing_is_whole(std::span<const uint8_t> d, std::size_t frame_len, bool final) const;
  bool verify_signature(std::span<const uint8_t> frame, std::size_t signed_len);
  void note_garbage(std::size_t n);

  const MessageSet* messages_;
  ParserOptions options_;
  ParserStats stats_;
  std::vector<uint8_t> pending_;  ///< stream bytes of a frame not yet complete
  Frame frame_;
  bool in_garbage_ = false;
  std::map<std::tuple<uint8_t, uint8_t, uint8_t>, uint64_t> last_timestamp_;  ///< (link, sysid, compid)
};

}  // namespace hitl::mavlink
