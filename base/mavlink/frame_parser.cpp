#include "base/mavlink/frame_parser.h"

#include <algorithm>
#include <cstring>

#include "base/mavlink/crc.h"

namespace hitl::mavlink {

FrameParser::FrameParser(const MessageSet& messages, ParserOptions options)
    : messages_(&messages), options_(std::move(options)) {
  pending_.reserve(2 * kMaxFrameLen);
}

void FrameParser::note_garbage(std::size_t n) {
  if (n == 0) return;
  stats_.garbage_bytes += n;
  if (!in_garbage_) ++stats_.parse_errors;
  in_garbage_ = true;
}

bool FrameParser::verify_signature(std::span<const uint8_t> frame, std::size_t signed_len) {
  const uint8_t* sig = frame.data() + signed_len;
  uint64_t timestamp = 0;
  for (int i = 6; i >= 1; --i) timestamp = (timestamp << 8) | sig[i];
  const auto expected = compute_signature(*options_.signing_key, frame.first(signed_len), sig[0], timestamp);
  if (!std::equal(expected.begin(), expected.end(), sig + 7)) return false;
  // Replay protection: per (link id, sysid, compid) the timestamp must advance.
  auto key = std::make_tuple(sig[0], frame[5], frame[6]);
  auto [it, inserted] = last_timestamp_.try_emplace(key, timestamp);
  if (!inserted) {
    if (timestamp <= it->second) return false;
    it->second = timestamp;
  }
  return true;
}

bool FrameParser::checksum_matches(std::span<const uint8_t> d, std::size_t header_len, std::size_t len, uint8_t crc_extra) {
  const uint16_t wire_crc = static_cast<uint16_t>(d[header_len + len] | (d[header_len + len + 1] << 8));
  return crc_accumulate(crc_extra, crc_x25(d.subspan(1, header_len - 1 + len))) == wire_crc;
}

std::optional<uint8_t> FrameParser::crc_extra_of(uint32_t msgid, const MessageDesc* desc) {
  if (desc != nullptr) return desc->crc_extra;  // a dialect may redefine a standard id
  if (const MessageCheck* check = find_standard_check(msgid)) return check->crc_extra;
  return std::nullopt;
}

FrameParser::Check FrameParser::checked_frame_at(std::span<const uint8_t> d) const {
  if (d.empty() || (d[0] != kStxV2 && d[0] != kStxV1)) return Check::No;
  const bool v2 = d[0] == kStxV2;
  const std::size_t header_len = v2 ? kHeaderLenV2 : kHeaderLenV1;
  if (d.size() < header_len) return Check::Unknown;
  const std::size_t len = d[1];
  const uint32_t msgid = v2 ? (uint32_t{d[7]} | (uint32_t{d[8]} << 8) | (uint32_t{d[9]} << 16)) : d[5];
  const auto crc_extra = crc_extra_of(msgid, messages_->find(msgid));
  if (!crc_extra) return Check::No;
  if (d.size() < header_len + len + kChecksumLen) return Check::Unknown;
  return checksum_matches(d, header_len, len, *crc_extra) ? Check::Yes : Check::No;
}

FrameParser::Check FrameParser::framing_is_whole(std::span<const uint8_t> d, std::size_t frame_len, bool final) const {
  // It ends where the data ends (a datagram's end; a stream waits for the next byte) or where the
  // next frame starts...
  if (frame_len == d.size()) {
    if (!final) return Check::Unknown;
  } else if (d[frame_len] != kStxV2 && d[frame_len] != kStxV1) {
    return Check::No;
  }
  // ...and it does not cover a frame whose checksum holds (that frame is the real one). A stream
  // waits until each start byte inside it can be judged.
  bool unknown = false;
  for (std::size_t i = 1; i < frame_len; ++i) {
    const Check inner = checked_frame_at(d.subspan(i));
    if (inner == Check::Yes) return Check::No;
    unknown = unknown || inner == Check::Unknown;
  }
  return unknown && !final ? Check::Unknown : Check::Yes;
}

FrameParser::Candidate FrameParser::try_frame(std::span<const uint8_t> d, bool final, std::size_t& frame_len) {
  const bool v2 = d[0] == kStxV2;
  const std::size_t header_len = v2 ? kHeaderLenV2 : kHeaderLenV1;
  if (d.size() < header_len) return Candidate::NeedMore;
  const uint8_t len = d[1];
  uint8_t incompat = 0;
  uint32_t msgid = 0;
  if (v2) {
    incompat = d[2];
    if ((incompat & ~kIncompatFlagSigned) != 0) {
      ++stats_.bad_incompat_flags;
      return Candidate::Reject;
    }
    msgid = uint32_t{d[7]} | (uint32_t{d[8]} << 8) | (uint32_t{d[9]} << 16);
  } else {
    msgid = d[5];
  }
  const bool is_signed = (incompat & kIncompatFlagSigned) != 0;
  const std::size_t signed_len = header_len + len + kChecksumLen;
  frame_len = signed_len + (is_signed ? kSignatureLen : 0);
  if (d.size() < frame_len) return Candidate::NeedMore;

  const MessageDesc* desc = messages_->find(msgid);
  const uint16_t wire_crc = static_cast<uint16_t>(d[header_len + len] | (d[header_len + len + 1] << 8));
  if (const auto crc_extra = crc_extra_of(msgid, desc)) {
    if (!checksum_matches(d, header_len, len, *crc_extra)) {
      ++stats_.crc_errors;
      return Candidate::Reject;
    }
  } else {
    // An id the set does not know: its checksum cannot be checked, so only whole framing vouches for it.
    const Check whole = framing_is_whole(d, frame_len, final);
    if (whole == Check::Unknown) return Candidate::NeedMore;
    ++stats_.unverified;
    if (whole == Check::No) {
      ++stats_.unverified_dropped;
      return Candidate::Reject;
    }
  }
  if (options_.signing_key) {
    if (is_signed && !verify_signature(d.first(frame_len), signed_len)) {
      ++stats_.signature_errors;
      return Candidate::SkipWhole;
    }
    if (!is_signed && !options_.accept_unsigned) {
      ++stats_.unsigned_rejected;
      return Candidate::SkipWhole;
    }
  }

  Frame& f = frame_;
  f.version = v2 ? Version::V2 : Version::V1;
  f.incompat_flags = incompat;
  f.compat_flags = v2 ? d[3] : 0;
  f.seq = v2 ? d[4] : d[2];
  f.sysid = v2 ? d[5] : d[3];
  f.compid = v2 ? d[6] : d[4];
  f.msgid = msgid;
  f.payload_len = len;
  std::memcpy(f.payload.data(), d.data() + header_len, len);
  std::memset(f.payload.data() + len, 0, kMaxPayloadLen - len);
  f.checksum = wire_crc;
  if (is_signed) std::memcpy(f.signature.data(), d.data() + signed_len, kSignatureLen);
  std::memcpy(f.raw.data(), d.data(), frame_len);
  f.raw_len = static_cast<uint16_t>(frame_len);
  f.desc = desc;
  f.check = find_standard_check(msgid);
  return Candidate::Frame;
}

std::size_t FrameParser::process(std::span<const uint8_t> data, bool final, const FrameHandler& on_frame) {
  std::size_t pos = 0;
  while (pos < data.size()) {
    const uint8_t* start = data.data() + pos;
    const uint8_t* stx = std::find_if(start, data.data() + data.size(), [](uint8_t b) { return b == kStxV2 || b == kStxV1; });
    note_garbage(static_cast<std::size_t>(stx - start));
    pos = static_cast<std::size_t>(stx - data.data());
    if (pos >= data.size()) break;

    std::size_t frame_len = 0;
    switch (try_frame(data.subspan(pos), final, frame_len)) {
      case Candidate::Frame:
        in_garbage_ = false;
        ++stats_.frames;
        if (frame_.version == Version::V1) ++stats_.v1_frames;
        if (frame_.is_signed()) ++stats_.signed_frames;
        if (frame_.desc == nullptr && frame_.check == nullptr) ++stats_.unknown_ids;
        else if (frame_.desc == nullptr) ++stats_.untyped_frames;
        pos += frame_len;
        on_frame(frame_);
        break;
      case Candidate::NeedMore:
        if (!final) return pos;
        ++stats_.truncated;
        note_garbage(1);
        pos += 1;
        break;
      case Candidate::Reject:
        note_garbage(1);
        pos += 1;
        break;
      case Candidate::SkipWhole:
        in_garbage_ = false;
        pos += frame_len;
        break;
    }
  }
  return data.size();
}

void FrameParser::feed(std::span<const uint8_t> bytes, const FrameHandler& on_frame) {
  stats_.bytes += bytes.size();
  if (pending_.empty()) {
    const std::size_t used = process(bytes, false, on_frame);
    pending_.assign(bytes.begin() + static_cast<std::ptrdiff_t>(used), bytes.end());
    return;
  }
  pending_.insert(pending_.end(), bytes.begin(), bytes.end());
  const std::size_t used = process(pending_, false, on_frame);
  pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(used));
}

void FrameParser::parse_datagram(std::span<const uint8_t> datagram, const FrameHandler& on_frame) {
  stats_.bytes += datagram.size();
  pending_.clear();
  in_garbage_ = false;
  process(datagram, true, on_frame);
  in_garbage_ = false;
}

}  // namespace hitl::mavlink
