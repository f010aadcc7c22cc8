// libFuzzer target for what hitl reads from PX4 SITL when it starts it (hitl sim --px4): the
// console file PX4 writes, read as it grows (engine/px4/px4_process.h: Px4Console, split in reads
// at input-derived sizes), each line's severity, a refused parameter's name and the prompt a MAVLink
// shell leaves; and a --px4-param value. Lines are bounded, parsed names are PX4's, refusals name the value.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

#include "engine/px4/px4_process.h"
#include "tests/fuzz/fuzz_check.h"

namespace {

bool is_name_char(char c) { return (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_'; }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* bytes, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(bytes), size);
  // --px4-param NAME=VALUE: a PX4 name and a finite number, or an input error.
  auto param = hitl::px4::parse_px4_param(text);
  if (param) {
    FUZZ_CHECK(!param->name.empty() && param->name.size() <= 16);
    for (const char c : param->name) FUZZ_CHECK(is_name_char(c));
  } else {
    FUZZ_CHECK(param.error().kind == hitl::ErrorKind::Input && !param.error().message.empty());
  }
  // The console, as PX4 writes it: read back in pieces whose size the first byte picks.
  char path[] = "/tmp/hitl-px4-console-fuzz-XXXXXX";
  const int fd = ::mkstemp(path);
  if (fd < 0) return 0;
  const bool written = ::write(fd, bytes, size) == static_cast<ssize_t>(size);
  ::close(fd);
  if (written) {
    hitl::px4::Px4Console console(path);
    const std::size_t piece = size == 0 ? 1 : 1 + bytes[0] % 97;
    std::size_t lines = 0;
    for (int reads = 0; reads < 4096; ++reads) {
      const auto got = console.new_lines(piece);
      for (const auto& line : got) {
        FUZZ_CHECK(line.size() <= 4096 + piece);  // a line without end is given out in pieces
        FUZZ_CHECK(line.find('\n') == std::string::npos);
        FUZZ_CHECK(hitl::px4::without_shell_prompt(line).rfind("pxh> ", 0) != 0);
        (void)hitl::px4::px4_console_severity(line);
        if (const auto name = hitl::px4::px4_unknown_parameter(line)) FUZZ_CHECK(!name->empty() && name->size() < line.size());
        ++lines;
      }
      if (got.empty() && reads * piece > size + 1) break;
    }
    FUZZ_CHECK(lines <= size + 1);
    FUZZ_CHECK(console.last_lines(12).size() <= 12);
  }
  ::unlink(path);
  return 0;
}
