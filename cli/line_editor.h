// Line editing and history for `hitl shell` at a terminal, from libedit (BSD): arrows and Emacs keys
// move in the line, Up/Down recall earlier commands, Ctrl-R searches them. The history is kept in
// $XDG_STATE_HOME/hitl/shell_history (~/.local/state/hitl/... without it), bounded to kMaxLines.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

namespace hitl::cli {

class LineEditor {
 public:
  static constexpr std::size_t kMaxLines = 1000;

  /// Reads the history file (when there is one) for Up/Down and Ctrl-R.
  explicit LineEditor(std::string history_path);
  /// Writes the history back (it is also written after each line), at most kMaxLines lines.
  ~LineEditor();
  LineEditor(const LineEditor&) = delete;
  LineEditor& operator=(const LineEditor&) = delete;

  /// One line typed after `prompt`; nullopt at end of input (Ctrl-D on an empty line).
  std::optional<std::string> read(const std::string& prompt);

 private:
  void save() const;

  std::string history_path_;
};

/// $XDG_STATE_HOME/hitl/shell_history, or $HOME/.local/state/hitl/shell_history; empty when neither
/// variable is set (no history file is kept then).
std::string shell_history_path();

}  // namespace hitl::cli
