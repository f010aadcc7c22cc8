// libFuzzer target for `hitl report --ulog FILE` (engine/ulog): PX4's ULog from anywhere, read for
// the topics a report asks for. Whatever the bytes, the reader returns a named error or a log whose
// every growing part is within its limits; the samples it keeps are the fields asked for, one value
// per field per timestamp. The input is the whole file.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "engine/ulog/ulog.h"
#include "tests/fuzz/fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* bytes, std::size_t size) {
  using namespace hitl::ulog;
  std::istringstream in(std::string(reinterpret_cast<const char*>(bytes), size));
  Limits limits;
  limits.max_formats = 64;
  limits.max_format_bytes = 1 << 16;
  limits.max_subscriptions = 64;
  limits.max_info = 32;
  limits.max_parameters = 32;
  limits.max_strings = 16;
  limits.max_text_bytes = 64;
  limits.max_samples = 1000;
  const std::vector<Request> requests = {{"vehicle_local_position", {"x", "y", "z"}, 0},
                                         {"vehicle_attitude", {"q[0]", "q[3]"}, 0},
                                         {"pos", {"x", "q[1]"}, 0},
                                         {"outer", {"after"}, 1}};
  auto log = parse_ulog(in, "fuzz.ulg", requests, limits);
  if (!log) {
    FUZZ_CHECK(!log.error().message.empty() && log.error().message.find("fuzz.ulg") != std::string::npos);
    FUZZ_CHECK(log.error().kind == hitl::ErrorKind::Input);
    return 0;
  }
  FUZZ_CHECK(log->bytes <= size);
  FUZZ_CHECK(log->info.size() <= limits.max_info && log->parameters.size() <= limits.max_parameters);
  FUZZ_CHECK(log->strings.size() <= limits.max_strings && log->topics.size() <= limits.max_subscriptions);
  FUZZ_CHECK(log->series.size() == requests.size());
  std::size_t samples = 0;
  for (std::size_t r = 0; r < log->series.size(); ++r) {
    const auto& s = log->series[r];
    FUZZ_CHECK(s.values.size() == requests[r].fields.size());
    for (const auto& v : s.values) FUZZ_CHECK(v.size() == s.timestamp_us.size());
    FUZZ_CHECK(s.size() > 0 || !s.missing.empty());
    samples += s.size();
  }
  FUZZ_CHECK(samples <= limits.max_samples);
  for (const auto& [k, v] : log->info) FUZZ_CHECK(k.size() <= 67 && v.size() <= limits.max_text_bytes + 3);
  for (const auto& s : log->strings) FUZZ_CHECK(s.text.size() <= limits.max_text_bytes + 3);
  FUZZ_CHECK(log->notes.size() <= 100);
  return 0;
}
