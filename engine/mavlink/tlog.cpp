#include "engine/mavlink/tlog.h"

#include <cerrno>
#include <cstring>

#include "base/mavlink/frame.h"

namespace hitl::mavlink {

Expected<TlogWriter> TlogWriter::open(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) return Error::unavailable("cannot write tlog '" + path + "': " + std::strerror(errno));
  TlogWriter w;
  w.file_.reset(f);
  w.path_ = path;
  return w;
}

bool TlogWriter::write(uint64_t time_unix_us, std::span<const uint8_t> frame) {
  if (!ok_) return false;
  uint8_t stamp[8];
  for (int i = 0; i < 8; ++i) stamp[i] = static_cast<uint8_t>(time_unix_us >> (56 - 8 * i));
  if (std::fwrite(stamp, 1, 8, file_.get()) != 8 || std::fwrite(frame.data(), 1, frame.size(), file_.get()) != frame.size())
    fail();
  return ok_;
}

bool TlogWriter::flush() {
  if (ok_ && std::fflush(file_.get()) != 0) fail();
  return ok_;
}

void TlogWriter::fail() {
  ok_ = false;
  error_ = "writing '" + path_ + "' failed: " + std::strerror(errno);
}

std::size_t frame_length_from_header(std::span<const uint8_t> bytes) {
  if (bytes.size() < 3) return 0;
  if (bytes[0] == kStxV2)
    return kHeaderLenV2 + bytes[1] + kChecksumLen + ((bytes[2] & kIncompatFlagSigned) ? kSignatureLen : 0);
  if (bytes[0] == kStxV1) return kHeaderLenV1 + bytes[1] + kChecksumLen;
  return 0;
}

Expected<TlogReader> TlogReader::open(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) return Error::input("cannot read tlog '" + path + "': " + std::strerror(errno));
  TlogReader r;
  r.file_.reset(f);
  return r;
}

bool TlogReader::fill(std::size_t need) {
  if (buf_.size() - pos_ >= need) return true;
  if (pos_ > 0) {
    buf_.erase(buf_.begin(), buf_.begin() + static_cast<std::ptrdiff_t>(pos_));
    pos_ = 0;
  }
  while (!eof_ && buf_.size() < need) {
    uint8_t chunk[65536];
    const std::size_t n = std::fread(chunk, 1, sizeof chunk, file_.get());
    if (n == 0) eof_ = true;
    buf_.insert(buf_.end(), chunk, chunk + n);
  }
  return buf_.size() >= need;
}

bool TlogReader::next(TlogRecord& record) {
  while (fill(8 + 3)) {
    const std::span<const uint8_t> rest(buf_.data() + pos_ + 8, buf_.size() - pos_ - 8);
    const std::size_t len = frame_length_from_header(rest);
    if (len == 0) {  // not a timestamp followed by a frame: slide one byte and look again
      ++pos_;
      ++stats_.skipped_bytes;
      continue;
    }
    if (!fill(8 + len)) {  // the file ends inside this frame
      ++stats_.truncated;
      stats_.skipped_bytes += buf_.size() - pos_;
      pos_ = buf_.size();
      return false;
    }
    uint64_t t = 0;
    for (int i = 0; i < 8; ++i) t = (t << 8) | buf_[pos_ + static_cast<std::size_t>(i)];
    record.time_unix_us = t;
    record.frame.assign(buf_.begin() + static_cast<std::ptrdiff_t>(pos_ + 8),
                        buf_.begin() + static_cast<std::ptrdiff_t>(pos_ + 8 + len));
    pos_ += 8 + len;
    ++stats_.records;
    return true;
  }
  stats_.skipped_bytes += buf_.size() - pos_;
  pos_ = buf_.size();
  return false;
}

}  // namespace hitl::mavlink
