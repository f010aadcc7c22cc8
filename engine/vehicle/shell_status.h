// What a PX4 shell command returned, read from its output. PX4's shells print a status only when a
// command fails:
//   pxh (posix: the VOXL2, SITL)  "Command 'NAME' failed, returned N."   (N: the command's return)
//                                 "Invalid command: NAME"                  (returns -1)
//   nsh (NuttX), hitl target      "nsh: NAME: command not found"
#pragma once

#include <string>

namespace hitl::vehicle {

struct ShellStatus {
  int code = 0;      ///< 0: nothing in the output says the command failed
  std::string line;  ///< the line that says so (empty when code is 0)
};

/// The last failure line of `output`, if any.
ShellStatus shell_status(const std::string& output);

}  // namespace hitl::vehicle
