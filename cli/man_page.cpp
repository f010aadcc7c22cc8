#include "cli/man_page.h"

#include <cstdio>
#include <algorithm>
#include <sstream>

#include "cli/option_words.h"

namespace hitl::cli {
namespace {

/// The next code point of UTF-8 text at `i` (advancing it); invalid bytes come back as U+FFFD.
uint32_t next_code_point(const std::string& s, std::size_t& i) {
  const auto b = static_cast<unsigned char>(s[i++]);
  int extra = b >= 0xF0 ? 3 : b >= 0xE0 ? 2 : b >= 0xC0 ? 1 : 0;
  if (b >= 0x80 && extra == 0) return 0xFFFD;
  uint32_t cp = extra == 0 ? b : (b & (0x3F >> extra));
  for (; extra > 0; --extra) {
    if (i >= s.size() || (static_cast<unsigned char>(s[i]) & 0xC0) != 0x80) return 0xFFFD;
    cp = (cp << 6) | (static_cast<unsigned char>(s[i++]) & 0x3F);
  }
  return cp;
}

std::string bold(const std::string& s) { return "\\fB" + roff_escape(s) + "\\fR"; }
std::string italic(const std::string& s) { return "\\fI" + roff_escape(s) + "\\fR"; }

std::string sentence(std::string s) {
  while (!s.empty() && (s.back() == ' ' || s.back() == '\n')) s.pop_back();
  if (!s.empty() && s.back() != '.' && s.back() != '!' && s.back() != '?') s += '.';
  return s;
}

/// The option's tag line: "\fB\-i\fR, \fB\-\-target\-ip\fR \fITEXT\fR".
std::string option_tag(const OptionModel& o) {
  if (!o.positional.empty()) return italic(o.positional);
  std::string tag;
  for (const auto& s : o.spellings()) tag += (tag.empty() ? "" : ", ") + bold(s);
  if (!o.is_flag()) {
    const std::string value = italic(o.type_name.empty() ? "VALUE" : o.type_name);
    tag += " " + (o.optional_value() ? "[" + value + "]" : value);
  }
  return tag;
}

void write_option(std::ostringstream& out, const OptionModel& o) {
  out << ".TP\n" << option_tag(o) << "\n" << roff_escape(sentence(o.description)) << "\n";
  std::vector<std::string> notes;
  if (const auto c = option_constraints(o); !c.empty()) notes.push_back("Accepts " + c + ".");
  if (!o.default_value.empty()) {
    const auto unit = option_unit(o);
    notes.push_back("Default: " + o.default_value + (unit.empty() || unit == "%" ? unit : " " + unit) + ".");
  }
  if (o.repeatable && !o.is_flag()) notes.push_back("May be given more than once.");
  if (o.required) notes.push_back("Required.");
  for (const auto& n : notes) out << roff_escape(n) << "\n";
}

void write_options(std::ostringstream& out, const std::vector<const OptionModel*>& options) {
  std::vector<std::string> groups;
  for (const auto* o : options)
    if (std::find(groups.begin(), groups.end(), o->group) == groups.end()) groups.push_back(o->group);
  for (const auto& g : groups) {
    if (groups.size() > 1) out << ".PP\n" << italic(g + ":") << "\n";
    for (const auto* o : options)
      if (o->group == g) write_option(out, *o);
  }
}

void write_preformatted(std::ostringstream& out, const std::string& text) {
  out << ".PP\n.RS 4\n.nf\n";
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) out << (line.empty() ? "\\&" : roff_escape(line)) << "\n";
  out << ".fi\n.RE\n";
}

void write_command(std::ostringstream& out, const CommandModel& c) {
  out << ".SS \"" << roff_escape(c.full_name()) << "\"\n";
  out << bold(c.full_name()) << " [" << italic("OPTIONS") << "]";
  for (const auto* p : c.positionals())
    out << " " << (p->required ? italic(p->positional) : "[" + italic(p->positional) + "]") << (p->repeatable ? " ..." : "");
  if (!c.commands.empty()) out << " " << italic("COMMAND");
  out << "\n.PP\n" << roff_escape(sentence(c.description)) << "\n";
  std::vector<const OptionModel*> own;
  for (const auto& o : c.options) own.push_back(&o);
  write_options(out, own);
  if (c.path.size() > 1 && c.fallthrough)
    out << ".PP\nThe options of " << bold("hitl " + c.path.front()) << " apply here too.\n";
  if (!c.commands.empty()) {
    out << ".PP\nCommands:";
    for (std::size_t i = 0; i < c.commands.size(); ++i) out << (i ? ", " : " ") << bold(c.commands[i].name());
    out << ".\n";
  }
  if (!c.footer.empty()) write_preformatted(out, c.footer);
  for (const auto& s : c.commands) write_command(out, s);
}

void replace_line(std::string& text, const std::string& marker, const std::string& with) {
  const auto at = text.find(marker + "\n");
  if (at != std::string::npos) text.replace(at, marker.size() + 1, with);
}

}  // namespace

std::string roff_escape(const std::string& text) {
  std::string out;
  bool line_start = true;
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (line_start && (c == '.' || c == '\'')) out += "\\&";
    line_start = c == '\n';
    if (static_cast<unsigned char>(c) >= 0x80) {
      char buf[16];
      std::snprintf(buf, sizeof buf, "\\[u%04X]", next_code_point(text, i));
      out += buf;
      continue;
    }
    if (c == '\\') out += "\\e";
    else if (c == '-') out += "\\-";
    else out += c;
    ++i;
  }
  return out;
}

std::string man_page(const CommandModel& root, const std::string& template_roff, const std::string& version) {
  std::ostringstream global;
  std::vector<const OptionModel*> root_options;
  for (const auto& o : root.options) root_options.push_back(&o);
  write_options(global, root_options);

  std::ostringstream commands;
  for (const auto& c : root.commands) write_command(commands, c);

  std::string page = ".\\\" Generated by `hitl man` from hitl's command-line model and docs/man/hitl.1.in.\n"
                     ".\\\" Do not edit: edit those and run scripts/regen-completions.sh.\n" +
                     template_roff;
  replace_line(page, ".\\\" @GLOBAL_OPTIONS@", global.str());
  replace_line(page, ".\\\" @COMMANDS@", commands.str());
  for (auto at = page.find("@VERSION@"); at != std::string::npos; at = page.find("@VERSION@", at))
    page.replace(at, 9, roff_escape(version));
  return page;
}

}  // namespace hitl::cli
