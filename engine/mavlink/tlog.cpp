#include "engine/mavlink/tlog.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

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

void TlogReader::Closer::operator()(int* fd) const {
  ::close(*fd);
  delete fd;
}

Expected<TlogReader> TlogReader::open(const std::string& path, TlogInput input) {
  // Non-blocking: opening a FIFO with no writer returns at once (it would wait for one), and reads
  // wait in poll(), where `stop` is looked at.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return Error::input("cannot read tlog '" + path + "': " + std::strerror(errno));
  TlogReader r;
  r.fd_.reset(new int(fd));
  struct stat st {};
  if (::fstat(fd, &st) != 0) return Error::input("cannot read tlog '" + path + "': " + std::strerror(errno));
  const bool regular = S_ISREG(st.st_mode), pipe = S_ISFIFO(st.st_mode);
  if (!regular && !(pipe && input == TlogInput::FileOrPipe)) {
    const char* what = S_ISDIR(st.st_mode) ? "a directory" : S_ISCHR(st.st_mode) ? "a character device" : S_ISBLK(st.st_mode) ? "a block device"
                       : pipe ? "a pipe" : S_ISSOCK(st.st_mode) ? "a socket" : "not a regular file";
    return Error::input("tlog '" + path + "' is " + std::string(what) + ", not a log file (" +
                        (input == TlogInput::FileOrPipe ? "a regular file or a pipe" : "a regular file: it is read twice") + ")");
  }
  r.pipe_ = pipe;
  return r;
}

bool TlogReader::fill(std::size_t need) {
  if (buf_.size() - pos_ >= need) return true;
  if (pos_ > 0) {
    buf_.erase(buf_.begin(), buf_.begin() + static_cast<std::ptrdiff_t>(pos_));
    pos_ = 0;
  }
  while (!eof_ && buf_.size() < need) {
    if (stop_ != nullptr && stop_->load()) {
      stopped_ = eof_ = true;
      break;
    }
    if (pipe_) {
      // A FIFO whose writer has not come yet reads as the end; poll() waits for it (Linux reports
      // POLLHUP only once a writer has come and gone), as `cat` waits in open().
      pollfd p{*fd_, POLLIN, 0};
      if (::poll(&p, 1, 100) <= 0) continue;
    }
    uint8_t chunk[65536];
    const ssize_t n = ::read(*fd_, chunk, sizeof chunk);
    if (n > 0) {
      buf_.insert(buf_.end(), chunk, chunk + n);
    } else if (n == 0) {
      eof_ = true;
    } else if (errno == EAGAIN || errno == EWOULDBLOCK) {
      // A pipe with nothing to read yet (a FIFO whose writer has not come or not written).
      pollfd p{*fd_, POLLIN, 0};
      (void)::poll(&p, 1, 100);
    } else if (errno != EINTR) {
      eof_ = true;  // a read error ends the log where it is
    }
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
      if (stop_ != nullptr && stats_.skipped_bytes % 65536 == 0 && stop_->load()) {
        stopped_ = eof_ = true;
        return false;
      }
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
