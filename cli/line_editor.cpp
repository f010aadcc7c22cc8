#include "cli/line_editor.h"

// libedit's readline-compatible interface (editline/readline.h), not GNU readline.
#include <editline/readline.h>

#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace hitl::cli {

LineEditor::LineEditor(std::string history_path) : history_path_(std::move(history_path)) {
  using_history();
  stifle_history(static_cast<int>(kMaxLines));
  if (!history_path_.empty()) read_history(history_path_.c_str());  // absent on the first run: nothing to read
}

LineEditor::~LineEditor() { save(); }

void LineEditor::save() const {
  if (history_path_.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(std::filesystem::path(history_path_).parent_path(), ec);
  if (write_history(history_path_.c_str()) == 0) history_truncate_file(history_path_.c_str(), static_cast<int>(kMaxLines));
}

std::optional<std::string> LineEditor::read(const std::string& prompt) {
  char* raw = readline(prompt.c_str());
  if (raw == nullptr) return std::nullopt;
  std::string line(raw);
  std::free(raw);
  // Recalled by Up unless it repeats the previous entry (or is empty).
  const HIST_ENTRY* last = history_length > 0 ? history_get(history_base + history_length - 1) : nullptr;
  if (!line.empty() && (last == nullptr || line != last->line)) {
    add_history(line.c_str());
    save();  // at once: Ctrl-C ends hitl without the destructor
  }
  return line;
}

std::string shell_history_path() {
  const char* state = std::getenv("XDG_STATE_HOME");
  if (state != nullptr && *state == '/') return std::string(state) + "/hitl/shell_history";
  const char* home = std::getenv("HOME");
  if (home != nullptr && *home != '\0') return std::string(home) + "/.local/state/hitl/shell_history";
  return {};
}

}  // namespace hitl::cli
