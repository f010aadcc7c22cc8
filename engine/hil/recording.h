// --record FILE.tlog: everything the session sends and receives. A write error (a full disk) is
// said once, naming the file; the session runs on (the board needs its sensors) and ends with an
// error (SessionSnapshot::record_error).
#pragma once

#include <optional>
#include <span>
#include <string>

#include "base/common/clock.h"
#include "engine/mavlink/tlog.h"

namespace hitl::hil {

class Recording {
 public:
  Recording() = default;
  explicit Recording(mavlink::TlogWriter writer) : writer_(std::move(writer)) {}

  void record(std::span<const uint8_t> bytes) {
    if (writer_ && writer_->ok()) writer_->write(static_cast<uint64_t>(unix_time_ns() / 1000), bytes);
  }
  void flush() {
    if (writer_) writer_->flush();
  }
  /// Recording at all (--record given).
  bool active() const { return writer_.has_value(); }
  /// The failure in words, once (empty when there is nothing new to say).
  std::string take_failure() {
    if (!writer_ || writer_->ok() || warned_) return {};
    warned_ = true;
    return "--record: " + writer_->error() + "; recording stopped, the session runs on";
  }
  /// The file and why it failed; empty when fine or not recording.
  std::string error() const { return writer_ ? writer_->error() : std::string{}; }

 private:
  std::optional<mavlink::TlogWriter> writer_;
  bool warned_ = false;
};

}  // namespace hitl::hil
