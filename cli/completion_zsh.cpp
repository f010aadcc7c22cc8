// The zsh completion: one _arguments function per command of the model, subcommands dispatched
// through _arguments' ->state, as zsh's own completions do.
#include <sstream>

#include "cli/completions.h"

namespace hitl::cli {
namespace {

/// For inside '...': ' becomes '\''.
std::string sq(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out;
}

/// Text inside an _arguments [description]: brackets and backslashes escaped.
std::string desc(const std::string& s) {
  std::string out;
  for (char c : summary(s)) {
    if (c == '[' || c == ']' || c == '\\') out += '\\';
    out += c;
  }
  return sq(out);
}

/// An _arguments message or _describe entry: colons and backslashes escaped.
std::string colon_escaped(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == ':' || c == '\\') out += '\\';
    out += c;
  }
  return sq(out);
}

std::string function_name(const CommandModel& c) {
  std::string name = "_hitl_cmd";
  for (const auto& p : c.path) {
    name += "_";
    for (char ch : p) name += std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
  }
  return name;
}

std::string action(const OptionModel& o) {
  switch (o.kind) {
    case ValueKind::None:
    case ValueKind::Text: return "";
    case ValueKind::Choice: {
      std::string out = "(";
      for (const auto& c : o.choices) {
        if (out.size() > 1) out += ' ';
        for (char ch : c) {
          if (ch == ' ' || ch == '(' || ch == ')' || ch == '\\' || ch == ':') out += '\\';
          out += ch;
        }
      }
      return sq(out + ")");
    }
    case ValueKind::File: return o.file_pattern.empty() ? "_files" : "_files -g \"" + sq(o.file_pattern) + "\"";
    case ValueKind::Directory: return "_files -/";
    case ValueKind::MessageList: return "_hitl_messages";
    case ValueKind::MessageRates: return "_hitl_message_rates";
    case ValueKind::FaultSpec: return "_hitl_faults";
  }
  return "";
}

std::string value_message(const OptionModel& o) {
  const std::string m = !o.type_name.empty() ? o.type_name : (!o.positional.empty() ? o.positional : "value");
  return colon_escaped(m);
}

/// One _arguments spec for an option: '(EXCLUDED)--name=[description]:MESSAGE:ACTION', brace-expanded
/// over its spellings when it has several: '(-i --target-ip)'{-i+,--target-ip=}'[...]:...'.
std::string option_spec(const OptionModel& o) {
  std::vector<std::string> names;
  for (const auto& s : o.short_names) names.push_back("-" + s + (o.is_flag() ? "" : "+"));
  for (const auto& l : o.long_names) names.push_back("--" + l + (o.is_flag() ? "" : "="));
  std::string exclusion;
  if (o.help) {
    exclusion = "(- *)";
  } else if (o.repeatable) {
    exclusion = "*";
  } else {
    std::string list;
    for (const auto& s : o.spellings()) list += (list.empty() ? "" : " ") + s;
    exclusion = "(" + list + ")";
  }
  std::string rest = "[" + desc(o.description) + "]";
  if (!o.is_flag()) rest += std::string(o.optional_value() ? "::" : ":") + value_message(o) + ":" + action(o);
  if (names.size() == 1) return "'" + exclusion + names.front() + rest + "'";
  std::string spelled = "{";
  for (std::size_t i = 0; i < names.size(); ++i) spelled += (i ? "," : "") + names[i];
  return "'" + exclusion + "'" + spelled + "}'" + rest + "'";
}

std::string positional_spec(const OptionModel& p, std::size_t index, bool last) {
  const std::string position = (p.repeatable && last) ? "*" : std::to_string(index + 1);
  return "'" + position + (p.required || position == "*" ? ":" : "::") + value_message(p) + ":" + action(p) + "'";
}

void write_command(std::ostringstream& out, const CommandModel& root, const CommandModel& c) {
  const std::string fn = function_name(c);
  out << fn << "() {\n";
  if (!c.commands.empty()) out << "    local curcontext=\"$curcontext\" state state_descr line\n    typeset -A opt_args\n";
  out << "    _arguments " << (c.commands.empty() ? "" : "-C ") << "-s -S : \\\n";
  for (const auto* o : accepted_options(root, c.path)) out << "        " << option_spec(*o) << " \\\n";
  const auto positionals = c.positionals();
  for (std::size_t i = 0; i < positionals.size(); ++i)
    out << "        " << positional_spec(*positionals[i], i, i + 1 == positionals.size()) << " \\\n";
  if (!c.commands.empty()) {
    out << "        ': :" << fn << "_commands' \\\n        '*:: :->command'\n";
    out << "    [[ $state == command ]] || return\n";
    std::string context = "hitl";
    for (const auto& p : c.path) context += "-" + p;
    out << "    curcontext=\"${curcontext%:*:*}:" << sq(context) << "-$words[1]:\"\n";
    out << "    case $words[1] in\n";
    for (const auto& s : c.commands) out << "        " << s.name() << ") " << function_name(s) << " ;;\n";
    out << "    esac\n";
  } else {
    out << "        && return 0\n";
  }
  out << "}\n\n";
  if (!c.commands.empty()) {
    out << fn << "_commands() {\n    local -a commands=(\n";
    for (const auto& s : c.commands) out << "        '" << colon_escaped(s.name()) << ":" << sq(summary(s.description)) << "'\n";
    out << "    )\n    _describe -t commands '" << sq(c.full_name("hitl")) << " command' commands\n}\n\n";
  }
  for (const auto& s : c.commands) write_command(out, root, s);
}

}  // namespace

std::string zsh_completion(const CommandModel& root, const std::vector<std::string>& message_names,
                           const std::vector<std::string>& fault_names) {
  std::ostringstream out;
  out << "#compdef hitl\n"
         "# zsh completion for hitl. Generated by `hitl completion zsh` from hitl's command-line model.\n"
         "# Do not edit: run scripts/regen-completions.sh after changing a command or an option.\n"
         "# Install: as _hitl in a directory of $fpath (e.g. /usr/share/zsh/vendor-completions).\n\n";
  std::string names;
  for (const auto& n : message_names) names += " " + sq(n);
  out << "# MAVLink messages compiled into hitl (for --show, --expect).\n"
         "_hitl_messages() {\n    _values -s , 'MAVLink message'"
      << names << "\n}\n\n"
      << "_hitl_message_rates() {\n    local -a names=(" << (names.empty() ? "" : names.substr(1)) << ")\n"
      << "    compset -P '*,'\n    compadd -S = -- $names\n}\n\n";
  std::string faults;
  for (const auto& n : fault_names) faults += " " + sq(n);
  out << "# The faults hitl injects (for --fault): the name; its arguments are the user's.\n"
         "_hitl_faults() {\n    local -a names=(" << (faults.empty() ? "" : faults.substr(1)) << ")\n"
      << "    [[ $PREFIX == *[:@+]* ]] && return 1\n    compadd -S '' -- $names\n}\n\n";
  write_command(out, root, root);
  out << "_hitl() {\n    " << function_name(root) << " \"$@\"\n}\n\n"
         "if [[ \"${funcstack[1]}\" == _hitl ]]; then\n    _hitl \"$@\"\nelse\n    compdef _hitl hitl\nfi\n";
  return out.str();
}

}  // namespace hitl::cli
