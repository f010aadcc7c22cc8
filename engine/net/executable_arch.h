// Which machine an executable is built for, in `uname -m`'s words, so that hitl pushes the board a
// relay it can run (an x86-64 build of hitl-adb-relay does not start on a VOXL2's aarch64).
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace hitl::net {

/// "aarch64", "x86_64", "arm", "i386" or "elf-machine-N" from an ELF file's header; nullopt when
/// the file cannot be read or is not ELF.
std::optional<std::string> executable_architecture(const std::string& path);

/// `uname -m`'s answer in the same words ("armv7l" -> "arm", "arm64" -> "aarch64", "i686" -> "i386").
std::string normalize_machine(std::string_view uname_machine);

}  // namespace hitl::net
