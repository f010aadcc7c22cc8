// A ULog written byte by byte for tests (the format: engine/ulog/ulog.h): the header, messages of
// any type, well formed or not, as the tests need them.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

namespace hitl::test {

class ULogWriter {
 public:
  explicit ULogWriter(uint64_t start_us = 1000, uint8_t version = 1) {
    bytes_ = {'U', 'L', 'o', 'g', 0x01, 0x12, 0x35, version};
    put64(start_us);
  }
  /// A message of `type` with `payload` (its size in the header).
  ULogWriter& message(char type, const std::string& payload) {
    put16(static_cast<uint16_t>(payload.size()));
    bytes_.push_back(static_cast<uint8_t>(type));
    bytes_.insert(bytes_.end(), payload.begin(), payload.end());
    return *this;
  }
  ULogWriter& flag_bits(uint8_t incompat0 = 0, uint64_t appended_offset = 0, uint8_t incompat1 = 0) {
    std::string p(40, '\0');
    p[8] = static_cast<char>(incompat0);
    p[9] = static_cast<char>(incompat1);
    std::memcpy(p.data() + 16, &appended_offset, 8);
    return message('B', p);
  }
  ULogWriter& format(const std::string& text) { return message('F', text); }
  ULogWriter& info(const std::string& key, const std::string& value) {
    return message('I', std::string(1, static_cast<char>(key.size())) + key + value);
  }
  ULogWriter& parameter_float(const std::string& name, float v) {
    const std::string key = "float " + name;
    return message('P', std::string(1, static_cast<char>(key.size())) + key + raw(v));
  }
  ULogWriter& subscribe(uint16_t msg_id, const std::string& topic, uint8_t multi_id = 0) {
    return message('A', std::string(1, static_cast<char>(multi_id)) + raw(msg_id) + topic);
  }
  ULogWriter& data(uint16_t msg_id, const std::string& fields) { return message('D', raw(msg_id) + fields); }
  ULogWriter& logged(uint8_t level, uint64_t t_us, const std::string& text) {
    return message('L', std::string(1, static_cast<char>(level)) + raw(t_us) + text);
  }
  template <class T>
  static std::string raw(T v) {
    std::string s(sizeof v, '\0');
    std::memcpy(s.data(), &v, sizeof v);
    return s;
  }
  const std::vector<uint8_t>& bytes() const { return bytes_; }
  std::string text() const { return std::string(bytes_.begin(), bytes_.end()); }

 private:
  void put16(uint16_t v) { bytes_.push_back(static_cast<uint8_t>(v)), bytes_.push_back(static_cast<uint8_t>(v >> 8)); }
  void put64(uint64_t v) {
    for (int i = 0; i < 8; ++i) bytes_.push_back(static_cast<uint8_t>(v >> (8 * i)));
  }
  std::vector<uint8_t> bytes_;
};

}  // namespace hitl::test
