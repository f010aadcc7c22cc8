#include "engine/net/executable_arch.h"

#include <cstdint>
#include <fstream>

namespace hitl::net {

std::optional<std::string> executable_architecture(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char h[20] = {};
  if (!in.read(reinterpret_cast<char*>(h), sizeof h)) return std::nullopt;
  if (h[0] != 0x7F || h[1] != 'E' || h[2] != 'L' || h[3] != 'F') return std::nullopt;
  // e_ident[EI_DATA] (byte 5): 1 little-endian, 2 big-endian; e_machine is the u16 at byte 18.
  const uint16_t machine = h[5] == 2 ? static_cast<uint16_t>((h[18] << 8) | h[19]) : static_cast<uint16_t>((h[19] << 8) | h[18]);
  switch (machine) {
    case 183: return "aarch64";  // EM_AARCH64
    case 62: return "x86_64";    // EM_X86_64
    case 40: return "arm";       // EM_ARM
    case 3: return "i386";       // EM_386
    default: return "elf-machine-" + std::to_string(machine);
  }
}

std::string normalize_machine(std::string_view m) {
  if (m == "arm64" || m == "aarch64" || m == "aarch64_be") return "aarch64";
  if (m.substr(0, 3) == "arm") return "arm";
  if (m == "i386" || m == "i486" || m == "i586" || m == "i686" || m == "x86") return "i386";
  if (m == "amd64" || m == "x86_64") return "x86_64";
  return std::string(m);
}

}  // namespace hitl::net
