// PX4's ULog (docs.px4.io dev_log/ulog_file_format; docs/report.md "PX4's ULog"): a 16-byte
// header ("ULog" 0x01 0x12 0x35, version, start time in us), then messages, each a 3-byte header
// (uint16 msg_size without the header, uint8 msg_type) and msg_size bytes, little endian:
//   'B' flag bits (compat[8], incompat[8], appended_offsets[3] uint64); an unknown incompat bit
//       means the log cannot be read and is refused, as the spec requires
//   'F' format "name:type field;type[n] field;..." (a type is a basic one or another format)
//   'I' / 'M' / 'P' / 'Q' information, multi information, parameter, default parameter:
//       uint8 key_len, key "type name", value (M and Q have one byte more before key_len)
//   'A' subscription: uint8 multi_id, uint16 msg_id, topic name
//   'D' data: uint16 msg_id, the topic's bytes as its format lays them out (first field: uint64
//       timestamp, us; a trailing _padding may be left out)
//   'L' / 'C' logged string: uint8 level, [uint16 tag,] uint64 timestamp, text
//   'S' sync, 'O' dropout (uint16 ms), 'R' unsubscription; anything else is skipped by its size.
//
// read for what a report asks: the fields it names of the topics it names, the information, the
// parameters and the logged strings. Everything that grows with the input is bounded (Limits):
// more is counted and said in `notes`, never kept. A log cut in the middle of a message ends there
// (said). Not a ULog, a refused flag, a file that cannot be read: an Error naming the file.
#pragma once

#include <cstdint>
#include <istream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "base/common/expected.h"

namespace hitl::ulog {

struct Limits {
  uint64_t max_bytes = uint64_t{8} << 30;     ///< read this far (8 GiB), the rest said cut
  std::size_t max_formats = 4096;
  std::size_t max_format_bytes = 16 << 20;    ///< of format text kept over all formats (16 MiB)
  std::size_t max_subscriptions = 4096;
  std::size_t max_info = 4096;                ///< information entries kept ('I', 'M')
  std::size_t max_parameters = 8192;          ///< parameter names kept ('P')
  std::size_t max_strings = 2000;             ///< logged strings kept ('L', 'C')
  std::size_t max_text_bytes = 1024;          ///< of one kept value or string (longer: cut, said with "...")
  uint64_t max_samples = 20'000'000;          ///< samples kept over every requested topic
  int max_nesting = 16;                       ///< nested formats deeper than this are unusable
};

/// A topic's fields to read: top-level fields of a basic type, an array's element by index
/// ("x", "q[2]"); instance `multi_id` (0: the first).
struct Request {
  std::string topic;
  std::vector<std::string> fields;
  uint8_t multi_id = 0;
};

/// One request's samples: timestamp_us[i] with values[f][i] for fields[f]. Empty when the log has
/// no such topic (`missing` says why).
struct TopicSeries {
  Request request;
  std::vector<uint64_t> timestamp_us;
  std::vector<std::vector<double>> values;
  std::string missing;  ///< "" when the topic and its fields were found
  std::size_t size() const { return timestamp_us.size(); }
};

struct LoggedString {
  uint64_t timestamp_us = 0;
  uint8_t level = 0;  ///< '0' emergency .. '7' debug, as the Linux kernel's
  std::string text;
};

/// A parameter's defaults as PX4 logged them ('Q', only for a parameter whose value differs from one).
inline constexpr uint8_t kDefaultOfSystem = 1 << 0;        ///< the firmware's own default
inline constexpr uint8_t kDefaultOfCurrentSetup = 1 << 1;  ///< the default of the current setup (the airframe's)
struct ParameterDefault {
  std::optional<double> system;
  std::optional<double> current_setup;
};

struct ULogFile {
  std::string path;
  uint8_t version = 0;
  uint64_t start_us = 0;                        ///< the header's timestamp
  uint64_t bytes = 0;                           ///< read
  std::map<std::string, std::string> info;      ///< 'I' and 'M' by name ("ver_sw" -> "..."): text, numbers printed
  std::map<std::string, double> parameters;     ///< 'P', the last value of each
  std::map<std::string, ParameterDefault> parameter_defaults;  ///< 'Q' by name (bounded with `parameters`)
  std::vector<std::string> topics;              ///< subscribed, "name" or "name/N" for instance N > 0, in order
  std::vector<TopicSeries> series;              ///< one per request, in the requests' order
  std::vector<LoggedString> strings;
  uint64_t messages = 0;                        ///< messages read (header and payload whole)
  uint64_t dropouts = 0;                        ///< 'O' marks
  uint64_t dropout_ms = 0;                      ///< their total duration
  uint64_t unknown_messages = 0;                ///< types this reader does not know, skipped by their size
  uint64_t bad_messages = 0;                    ///< known types that did not parse (too short, unknown msg_id, ...)
  bool cut = false;                             ///< ended in the middle of a message (a log that stopped abruptly)
  std::vector<std::string> notes;               ///< what was dropped, cut or refused, in words
};

/// Reads a ULog from `in` (`path` names it in errors and notes).
Expected<ULogFile> parse_ulog(std::istream& in, const std::string& path, const std::vector<Request>& requests,
                              const Limits& limits = {});

/// Reads the ULog at `path`: an Input error when it cannot be read, is not a regular file, is not a
/// ULog or is refused.
Expected<ULogFile> read_ulog(const std::string& path, const std::vector<Request>& requests, const Limits& limits = {});

}  // namespace hitl::ulog
