#include "engine/ulog/ulog.h"

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <string_view>

#include "engine/ulog/ulog_format.h"

namespace hitl::ulog {
namespace {

constexpr std::array<uint8_t, 7> kMagic = {'U', 'L', 'o', 'g', 0x01, 0x12, 0x35};
constexpr std::size_t kHeaderBytes = 16;
constexpr std::size_t kMessageHeaderBytes = 3;
constexpr std::size_t kFlagBitsBytes = 40;  ///< compat[8], incompat[8], appended_offsets[3]
constexpr uint8_t kIncompatDataAppended = 0x01;

uint16_t u16(const uint8_t* p) { return static_cast<uint16_t>(p[0] | (p[1] << 8)); }
uint64_t u64(const uint8_t* p) {
  uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}

/// Printable text of at most `max` bytes (others as '?'), "..." when cut.
std::string text_of(std::string_view bytes, std::size_t max) {
  std::string out;
  for (char c : bytes.substr(0, max)) out.push_back(c >= 0x20 && c < 0x7f ? c : (c == '\n' || c == '\t' ? ' ' : '?'));
  while (!out.empty() && out.back() == ' ') out.pop_back();
  if (bytes.size() > max) out += "...";
  return out;
}

/// What one request reads of a subscription: where its fields lie.
struct Extract {
  std::size_t request = 0;       ///< index into the requests
  std::size_t timestamp_offset = 0;
  std::vector<FieldLocation> fields;
  std::size_t needed_bytes = 0;  ///< a sample shorter than this cannot give every field
};

/// A subscription and the requests that read it.
struct Subscription {
  std::string topic;
  uint8_t multi_id = 0;
  std::vector<Extract> extracts;
};

class Reader {
 public:
  Reader(std::istream& in, const std::string& path, const std::vector<Request>& requests, const Limits& limits)
      : in_(in), requests_(requests), limits_(limits) {
    log_.path = path;
    for (const auto& r : requests) log_.series.push_back({r, {}, std::vector<std::vector<double>>(r.fields.size()), ""});
  }

  Expected<ULogFile> run() {
    std::array<uint8_t, kHeaderBytes> header{};
    in_.read(reinterpret_cast<char*>(header.data()), header.size());
    if (static_cast<std::size_t>(in_.gcount()) < header.size() || !std::equal(kMagic.begin(), kMagic.end(), header.begin()))
      return Error::input("'" + log_.path + "' is not a ULog (no ULog header: it starts with \"ULog\" 0x01 0x12 0x35)");
    log_.version = header[7];
    log_.start_us = u64(header.data() + 8);
    if (log_.version > 1) note("file format version " + std::to_string(log_.version) + " (this reader knows 1): read as 1");
    uint64_t offset = kHeaderBytes;
    std::vector<uint8_t> payload;
    bool first = true;
    for (;;) {
      if (offset >= limits_.max_bytes) {
        if (in_.peek() != std::char_traits<char>::eof())
          note("the bytes after the first " + std::to_string(limits_.max_bytes) + " (the log was cut there)");
        break;
      }
      std::array<uint8_t, kMessageHeaderBytes> mh{};
      in_.read(reinterpret_cast<char*>(mh.data()), mh.size());
      const auto got = static_cast<std::size_t>(in_.gcount());
      if (got == 0) break;
      const uint16_t size = u16(mh.data());
      const uint8_t type = mh[2];
      // Appended data (a crash dump after a log that stopped mid-message) starts at its offset.
      if (appended_offset_ && offset < *appended_offset_ && offset + kMessageHeaderBytes + size > *appended_offset_) {
        if (!seek(*appended_offset_)) break;
        offset = *appended_offset_;
        appended_offset_.reset();
        continue;
      }
      if (got < mh.size()) {
        log_.cut = true;
        break;
      }
      payload.resize(size);
      in_.read(reinterpret_cast<char*>(payload.data()), size);
      if (static_cast<std::size_t>(in_.gcount()) < size) {
        log_.cut = true;
        break;
      }
      offset += kMessageHeaderBytes + size;
      ++log_.messages;
      if (first && type == 'B') {
        if (auto refused = flag_bits(payload)) return *refused;
      }
      first = false;
      handle(type, payload);
    }
    log_.bytes = offset;
    finish();
    return std::move(log_);
  }

 private:
  void note(std::string text) {
    if (log_.notes.size() < 100) log_.notes.push_back(std::move(text));
  }

  bool seek(uint64_t to) {
    in_.clear();
    in_.seekg(static_cast<std::streamoff>(to));
    return static_cast<bool>(in_);
  }

  std::optional<Error> flag_bits(const std::vector<uint8_t>& p) {
    if (p.size() < kFlagBitsBytes) {
      ++log_.bad_messages;
      return std::nullopt;
    }
    const uint8_t* incompat = p.data() + 8;
    bool unknown = (incompat[0] & ~kIncompatDataAppended) != 0;
    for (int i = 1; i < 8; ++i) unknown = unknown || incompat[i] != 0;
    if (unknown)
      return Error::input("'" + log_.path + "' sets incompatible ULog flags this reader does not know (a newer format): refused, as the ULog "
                          "specification requires");
    if ((incompat[0] & kIncompatDataAppended) != 0) {
      for (int k = 0; k < 3; ++k) {
        const uint64_t at = u64(p.data() + 16 + 8 * k);
        if (at != 0) {
          appended_offset_ = at;
          note("data appended at byte " + std::to_string(at) + " (read as part of the log)");
          break;
        }
      }
    }
    return std::nullopt;
  }

  void handle(uint8_t type, const std::vector<uint8_t>& p) {
    const std::string_view bytes(reinterpret_cast<const char*>(p.data()), p.size());
    switch (type) {
      case 'F': return format(bytes);
      case 'I': return info(bytes, 0, false);
      case 'M': return info(bytes, 1, false);
      case 'P': return info(bytes, 0, true);
      case 'Q': return parameter_default(bytes);
      case 'A': return subscribe(p);
      case 'D': return data(p);
      case 'L': return logged(p, 0);
      case 'C': return logged(p, 2);
      case 'O':
        if (p.size() < 2) break;
        ++log_.dropouts;
        log_.dropout_ms += u16(p.data());
        return;
      case 'B':
      case 'S':
      case 'R': return;
      default: ++log_.unknown_messages; return;
    }
    ++log_.bad_messages;
  }

  void format(std::string_view text) {
    auto f = parse_format(text);
    if (!f) {
      ++log_.bad_messages;
      return;
    }
    if ((formats_.size() >= limits_.max_formats && !formats_.count(f->name)) || format_bytes_ + text.size() > limits_.max_format_bytes) {
      ++formats_dropped_;
      return;
    }
    format_bytes_ += text.size();
    formats_[f->name] = std::move(*f);
  }

  /// 'Q': uint8 default_types (bit 0 the system's default, bit 1 the current setup's), then as 'P'.
  void parameter_default(std::string_view b) {
    if (b.size() < 2) return void(++log_.bad_messages);
    const auto types = static_cast<uint8_t>(b[0]);
    const std::size_t key_len = static_cast<uint8_t>(b[1]);
    if (b.size() < 2 + key_len) return void(++log_.bad_messages);
    const std::string_view key = b.substr(2, key_len), value = b.substr(2 + key_len);
    const auto space = key.find(' ');
    if (space == std::string_view::npos) return void(++log_.bad_messages);
    const std::string_view type = key.substr(0, space);
    const auto basic = basic_type(type);
    if (!basic || value.size() < basic_size(*basic)) return void(++log_.bad_messages);
    const std::string n = text_of(key.substr(space + 1), 64);
    if (log_.parameter_defaults.size() >= limits_.max_parameters && !log_.parameter_defaults.count(n))
      return void(++parameters_dropped_);
    const double v = decode_basic(*basic, reinterpret_cast<const uint8_t*>(value.data()));
    auto& d = log_.parameter_defaults[n];
    if (types & kDefaultOfSystem) d.system = v;
    if (types & kDefaultOfCurrentSetup) d.current_setup = v;
  }

  /// 'I' / 'M' / 'P': [skip bytes] uint8 key_len, key "type name", value.
  void info(std::string_view b, std::size_t skip, bool parameter) {
    if (b.size() < skip + 1) return void(++log_.bad_messages);
    const std::size_t key_len = static_cast<uint8_t>(b[skip]);
    if (b.size() < skip + 1 + key_len) return void(++log_.bad_messages);
    const std::string_view key = b.substr(skip + 1, key_len), value = b.substr(skip + 1 + key_len);
    const auto space = key.find(' ');
    if (space == std::string_view::npos) return void(++log_.bad_messages);
    const std::string_view type = key.substr(0, space), name = key.substr(space + 1);
    const auto basic = basic_type(type.substr(0, type.find('[')));
    if (parameter) {
      if (!basic || value.size() < basic_size(*basic) || type.find('[') != std::string_view::npos)
        return void(++log_.bad_messages);
      const std::string n = text_of(name, 64);
      if (log_.parameters.size() >= limits_.max_parameters && !log_.parameters.count(n)) return void(++parameters_dropped_);
      log_.parameters[n] = decode_basic(*basic, reinterpret_cast<const uint8_t*>(value.data()));
      return;
    }
    std::string text;
    if (basic == BasicType::Char) {
      text = text_of(value, limits_.max_text_bytes);
    } else if (basic && type.find('[') == std::string_view::npos && value.size() >= basic_size(*basic)) {
      // %.9g: a float's or a double's digits in at most 16 characters (std::to_string wrote 1e300
      // as 300 digits); an integer type's value whole (at most 20 digits).
      const double v = decode_basic(*basic, reinterpret_cast<const uint8_t*>(value.data()));
      char digits[32];
      const bool floating = *basic == BasicType::Float || *basic == BasicType::Double;
      std::snprintf(digits, sizeof digits, floating ? "%.9g" : "%.0f", v);
      text = digits;
    } else {
      text = "(" + std::to_string(value.size()) + " bytes)";
    }
    const std::string n = text_of(name, 64);
    auto it = log_.info.find(n);
    if (it != log_.info.end()) {
      if (skip == 1 && it->second.size() < limits_.max_text_bytes)  // 'M' continued, within the limit
        it->second = text_of(it->second + text, limits_.max_text_bytes);
      return;
    }
    if (log_.info.size() >= limits_.max_info) return void(++info_dropped_);
    log_.info[n] = std::move(text);
  }

  void subscribe(const std::vector<uint8_t>& p) {
    if (p.size() < 4) return void(++log_.bad_messages);
    const uint8_t multi_id = p[0];
    const uint16_t msg_id = u16(p.data() + 1);
    const std::string topic = text_of({reinterpret_cast<const char*>(p.data() + 3), p.size() - 3}, 255);
    if (subscriptions_.count(msg_id)) return void(++log_.bad_messages);  // an id used twice: the first stands
    if (subscriptions_.size() >= limits_.max_subscriptions) return void(++subscriptions_dropped_);
    Subscription s{topic, multi_id, {}};
    log_.topics.push_back(multi_id == 0 ? topic : topic + "/" + std::to_string(multi_id));
    Layouts layouts(formats_, limits_.max_nesting);
    for (std::size_t r = 0; r < requests_.size(); ++r) {
      if (requests_[r].topic != topic || requests_[r].multi_id != multi_id || taken_.count(r)) continue;
      taken_.insert(r);
      const auto timestamp = layouts.locate(topic, "timestamp");
      if (!timestamp || timestamp->type != BasicType::UInt64) {
        log_.series[r].missing = "its format has no uint64_t timestamp";
        continue;
      }
      Extract e{r, timestamp->offset, {}, timestamp->offset + 8};
      for (const auto& name : requests_[r].fields) {
        auto at = layouts.locate(topic, name);
        if (!at) {
          log_.series[r].missing = "its format has no basic field " + name;
          break;
        }
        e.fields.push_back(*at);
        e.needed_bytes = std::max(e.needed_bytes, at->offset + basic_size(at->type));
      }
      if (log_.series[r].missing.empty()) s.extracts.push_back(std::move(e));
    }
    subscriptions_.emplace(msg_id, std::move(s));
  }

  void data(const std::vector<uint8_t>& p) {
    if (p.size() < 2) return void(++log_.bad_messages);
    const auto it = subscriptions_.find(u16(p.data()));
    if (it == subscriptions_.end()) return void(++log_.bad_messages);
    const uint8_t* d = p.data() + 2;
    for (const Extract& e : it->second.extracts) {
      if (p.size() - 2 < e.needed_bytes) {
        ++log_.bad_messages;
        continue;
      }
      if (samples_ >= limits_.max_samples) {
        ++samples_dropped_;
        continue;
      }
      auto& series = log_.series[e.request];
      series.timestamp_us.push_back(u64(d + e.timestamp_offset));
      for (std::size_t f = 0; f < e.fields.size(); ++f) series.values[f].push_back(decode_basic(e.fields[f].type, d + e.fields[f].offset));
      ++samples_;
    }
  }

  /// 'L' (tag_bytes 0) / 'C' (2): uint8 level, [uint16 tag], uint64 timestamp, text.
  void logged(const std::vector<uint8_t>& p, std::size_t tag_bytes) {
    const std::size_t head = 1 + tag_bytes + 8;
    if (p.size() < head) return void(++log_.bad_messages);
    if (log_.strings.size() >= limits_.max_strings) return void(++strings_dropped_);
    LoggedString s;
    s.level = p[0];
    s.timestamp_us = u64(p.data() + 1 + tag_bytes);
    s.text = text_of({reinterpret_cast<const char*>(p.data() + head), p.size() - head}, limits_.max_text_bytes);
    log_.strings.push_back(std::move(s));
  }

  void finish() {
    if (log_.cut) note("the last message was cut (the log ended in the middle of it, as a log that stopped abruptly does)");
    auto counted = [&](uint64_t n, const std::string& what) {
      if (n > 0) note(std::to_string(n) + " " + what);
    };
    counted(formats_dropped_, "formats beyond the first " + std::to_string(limits_.max_formats) + " or " +
                                  std::to_string(limits_.max_format_bytes) + " bytes of them");
    counted(subscriptions_dropped_, "subscriptions after the first " + std::to_string(limits_.max_subscriptions));
    counted(info_dropped_, "information entries after the first " + std::to_string(limits_.max_info));
    counted(parameters_dropped_, "parameters after the first " + std::to_string(limits_.max_parameters));
    counted(strings_dropped_, "logged strings after the first " + std::to_string(limits_.max_strings));
    counted(samples_dropped_, "samples after the first " + std::to_string(limits_.max_samples));
    counted(log_.bad_messages, "messages that did not parse (too short, an unknown subscription, a bad format)");
    counted(log_.unknown_messages, "messages of types this reader does not know (skipped)");
    if (log_.dropouts > 0)
      note(std::to_string(log_.dropouts) + " dropouts (" + std::to_string(log_.dropout_ms) + " ms PX4's logger could not write)");
    for (auto& s : log_.series)
      if (s.size() == 0 && s.missing.empty()) s.missing = "not in this log";
  }

  std::istream& in_;
  const std::vector<Request>& requests_;
  Limits limits_;
  ULogFile log_;
  std::map<std::string, Format> formats_;
  std::map<uint16_t, Subscription> subscriptions_;
  std::set<std::size_t> taken_;  ///< requests matched to a subscription (the first of that topic and instance)
  std::optional<uint64_t> appended_offset_;
  uint64_t samples_ = 0;
  std::size_t format_bytes_ = 0;
  uint64_t formats_dropped_ = 0, subscriptions_dropped_ = 0, info_dropped_ = 0, parameters_dropped_ = 0, strings_dropped_ = 0,
           samples_dropped_ = 0;
};

}  // namespace

Expected<ULogFile> parse_ulog(std::istream& in, const std::string& path, const std::vector<Request>& requests, const Limits& limits) {
  return Reader(in, path, requests, limits).run();
}

Expected<ULogFile> read_ulog(const std::string& path, const std::vector<Request>& requests, const Limits& limits) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec) return Error::input("cannot read the ULog '" + path + "': " + ec.message());
  if (!std::filesystem::is_regular_file(status)) return Error::input("the ULog '" + path + "' is not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error::input("cannot read the ULog '" + path + "': " + std::strerror(errno));
  return parse_ulog(in, path, requests, limits);
}

}  // namespace hitl::ulog
