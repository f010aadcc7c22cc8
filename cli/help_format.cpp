#include "cli/help_format.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <regex>
#include <sstream>

namespace hitl::cli {
namespace {

std::size_t terminal_width() {
  winsize ws{};
  if (::isatty(STDOUT_FILENO) == 1 && ::ioctl(STDOUT_FILENO, TIOCGWINSZ, &ws) == 0 && ws.ws_col >= 40) return ws.ws_col;
  return 80;
}

}  // namespace

std::string plain_type_text(const std::string& opts) {
  std::string s = opts;
  // CheckedTransformer: "ENUM:value in {attitude->1,velocity->0} OR {1,0}" -> "attitude|velocity".
  static const std::regex enum_re(R"(ENUM:value in \{([^}]*)\}( OR \{[^}]*\})?)");
  std::smatch m;
  while (std::regex_search(s, m, enum_re)) {
    std::string names, item;
    std::stringstream items(m[1].str());
    while (std::getline(items, item, ',')) names += (names.empty() ? "" : "|") + item.substr(0, item.find("->"));
    s = m.prefix().str() + names + m.suffix().str();
  }
  // Range: "UINT:INT in [1 - 65535]" -> "UINT 1..65535".
  s = std::regex_replace(s, std::regex(R"(:(INT|FLOAT|NUMBER)? ?in \[([^ \]]+) - ([^ \]]+)\])"), " $2..$3");
  // IsMember: ":{1.0,2.0}" -> " 1.0|2.0".
  s = std::regex_replace(s, std::regex(R"(:\{([^}]*)\})"), " {$1}");
  return s;
}

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

std::string HelpFormatter::make_option_opts(const CLI::Option* opt) const {
  return plain_type_text(CLI::Formatter::make_option_opts(opt));
}

std::string HelpFormatter::make_option(const CLI::Option* opt, bool is_positional) const {
  const std::string name = "  " + make_option_name(opt, is_positional) + make_option_opts(opt);
  const std::size_t column = get_column_width();
  const std::size_t room = width_ > column + 20 ? width_ - column : 40;
  const std::string desc = wrap_words(make_option_desc(opt), room);
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
