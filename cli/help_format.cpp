#include "cli/help_format.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <sstream>

#include "cli/command_model.h"
#include "cli/option_words.h"

namespace hitl::cli {
namespace {

std::size_t terminal_width() {
  winsize ws{};
  if (::isatty(STDOUT_FILENO) == 1 && ::ioctl(STDOUT_FILENO, TIOCGWINSZ, &ws) == 0 && ws.ws_col >= 40) return ws.ws_col;
  return 80;
}

}  // namespace

std::string wrap_words(const std::string& text, std::size_t width) {
  std::string out;
  std::stringstream paragraphs(text);
  std::string paragraph;
  bool first_paragraph = true;
  while (std::getline(paragraphs, paragraph)) {
    if (!first_paragraph) out += '\n';
    first_paragraph = false;
    std::stringstream words(paragraph);
    std::string word, line;
    while (words >> word) {
      if (!line.empty() && line.size() + 1 + word.size() > width) {
        out += line + '\n';
        line.clear();
      }
      line += (line.empty() ? "" : " ") + word;
    }
    out += line;
  }
  return out;
}

HelpFormatter::HelpFormatter() : width_(terminal_width()) { column_width(36); }

std::string HelpFormatter::make_option(const CLI::Option* opt, bool is_positional) const {
  const OptionModel o = read_option_model(*opt);
  std::string name = "  ";
  if (is_positional) {
    name += option_metavar(o);
  } else {
    std::string spellings;
    for (const auto& s : o.spellings()) spellings += (spellings.empty() ? "" : ", ") + s;
    name += spellings;
    if (const auto value = option_value_tag(o); !value.empty()) name += " " + value;
  }
  std::string text = as_sentence(o.description);
  for (const auto& note : option_notes(o)) text += (text.empty() ? "" : " ") + note;
  const std::size_t column = get_column_width();
  const std::size_t room = width_ > column + 20 ? width_ - column : 40;
  const std::string desc = wrap_words(text, room);
  std::string out = name;
  if (desc.empty()) return out + "\n";
  if (name.size() >= column) out += "\n" + std::string(column, ' ');
  else out += std::string(column - name.size(), ' ');
  for (char c : desc) {
    out += c;
    if (c == '\n') out += std::string(column, ' ');
  }
  return out + "\n";
}

}  // namespace hitl::cli
