#include "engine/board/board_shell.h"

namespace hitl::board {
namespace {

/// dpkg over USB takes a while; a PX4 start under systemd-run returns at once.
constexpr int kBoardCommandTimeout_ms = 120000;

}  // namespace

Expected<net::ProgramOutput> AdbBoardShell::run(const std::string& command) {
  return adb_.shell(command, kBoardCommandTimeout_ms);
}

Status AdbBoardShell::push(const std::string& local_path, const std::string& remote_path) {
  return adb_.push(local_path, remote_path);
}

}  // namespace hitl::board
