// Telemetry logs as MAVProxy and QGroundControl write them: each frame preceded by
// an 8-byte big-endian timestamp in microseconds since the Unix epoch.
#pragma once

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "base/common/expected.h"

namespace hitl::mavlink {

class TlogWriter {
 public:
  static Expected<TlogWriter> open(const std::string& path);
  /// Appends one frame; returns false (and stays failed) on a write error.
  bool write(uint64_t time_unix_us, std::span<const uint8_t> frame);
  bool flush();
  bool ok() const { return ok_; }
  /// After a failed write or flush: "writing 'PATH' failed: No space left on device" (what
  /// `inspect --record` and `sim --record` both say); empty while ok.
  const std::string& error() const { return error_; }
  const std::string& path() const { return path_; }

 private:
  struct Closer {
    void operator()(std::FILE* f) const { std::fclose(f); }
  };
  std::unique_ptr<std::FILE, Closer> file_;
  std::string path_;
  bool ok_ = true;
  std::string error_;
  void fail();
};

struct TlogRecord {
  uint64_t time_unix_us = 0;
  std::vector<uint8_t> frame;  ///< one MAVLink frame's bytes
};

struct TlogStats {
  uint64_t records = 0;
  uint64_t skipped_bytes = 0;  ///< bytes that did not form a timestamp + frame (corruption)
  uint64_t truncated = 0;      ///< a last record cut off by the end of the file (a killed writer)
};

/// What a TlogReader opens: a regular file only (a reader that goes over the log twice: report,
/// replay), or a stream too (a pipe or FIFO: `inspect --tlog <(ssh board cat x.tlog)`). Devices
/// (/dev/zero), directories and sockets are refused either way.
enum class TlogInput { RegularFile, FileOrPipe };

class TlogReader {
 public:
  static Expected<TlogReader> open(const std::string& path, TlogInput input = TlogInput::RegularFile);
  /// Reads the next record; false at the end of the file (or once `stop`, when set, turned true).
  bool next(TlogRecord& record);
  const TlogStats& stats() const { return stats_; }
  /// Waits on a pipe (a FIFO whose writer has written nothing yet) look at `stop` every 100 ms, as
  /// does a long run of garbage: next() returns false soon after it turns true.
  void set_stop(const std::atomic<bool>* stop) { stop_ = stop; }
  /// next() returned false because of `stop`, not the end of the file.
  bool stopped() const { return stopped_; }

 private:
  bool fill(std::size_t need);
  struct Closer {
    void operator()(int* fd) const;
  };
  std::unique_ptr<int, Closer> fd_;
  std::vector<uint8_t> buf_;
  std::size_t pos_ = 0;
  bool eof_ = false;
  bool pipe_ = false;  ///< read when poll() says so: a FIFO with no writer yet reads as the end
  bool stopped_ = false;
  const std::atomic<bool>* stop_ = nullptr;
  TlogStats stats_;
};

/// Length of the frame starting at `bytes` (v1 or v2) from its header, or 0 if it does not start with STX.
std::size_t frame_length_from_header(std::span<const uint8_t> bytes);

}  // namespace hitl::mavlink
