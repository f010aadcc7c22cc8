// The bash completion: tables generated from the model (subcommands, options and value kinds per
// command path) and one fixed function that walks the words before the cursor through them.
// Self-contained: it needs no bash-completion helpers.
#include <map>
#include <sstream>

#include "base/common/shell_quote.h"
#include "cli/completions.h"

namespace hitl::cli {
namespace {

std::string join_path(const std::vector<std::string>& path) {
  std::string out;
  for (const auto& p : path) out += (out.empty() ? "" : " ") + p;
  return out;
}

/// How a value completes, as _hitl_complete_value reads it; empty for a flag.
std::string value_kind(const OptionModel& o) {
  std::string kind;
  switch (o.kind) {
    case ValueKind::None: return {};
    case ValueKind::Text: kind = "text"; break;
    case ValueKind::Choice:
      kind = "choice";
      for (const auto& c : o.choices) kind += " " + c;
      break;
    case ValueKind::File: kind = o.file_pattern.empty() ? "file" : "file " + o.file_pattern; break;
    case ValueKind::Directory: kind = "dir"; break;
    case ValueKind::MessageList: kind = "messages"; break;
    case ValueKind::MessageRates: kind = "message-rates"; break;
    case ValueKind::FaultSpec: kind = "faults"; break;
  }
  return o.optional_value() ? "optional " + kind : kind;
}

constexpr const char* kWalker = R"bash(
# _hitl_complete_value CUR KIND [ARG...]: fills COMPREPLY with the values of one kind.
_hitl_complete_value() {
    local cur="$1" kind="$2" head=""
    shift 2
    case "$kind" in
        file)
            compopt -o filenames 2>/dev/null
            if [[ -n "${1:-}" ]]; then
                mapfile -t COMPREPLY < <(compgen -d -- "$cur"; compgen -f -X "!$1" -- "$cur")
            else
                mapfile -t COMPREPLY < <(compgen -f -- "$cur")
            fi ;;
        dir)
            compopt -o filenames 2>/dev/null
            mapfile -t COMPREPLY < <(compgen -d -- "$cur") ;;
        choice)
            mapfile -t COMPREPLY < <(compgen -W "$*" -- "$cur") ;;
        messages)
            [[ "$cur" == *,* ]] && head="${cur%,*},"
            mapfile -t COMPREPLY < <(compgen -P "$head" -W "$_hitl_messages" -- "${cur##*,}") ;;
        message-rates)
            [[ "$cur" == *,* ]] && head="${cur%,*},"
            compopt -o nospace 2>/dev/null
            mapfile -t COMPREPLY < <(compgen -P "$head" -S = -W "$_hitl_messages" -- "${cur##*,}") ;;
        faults)
            # The name only: its arguments, start and duration (":2,0.8@15+5") are the user's.
            [[ "$cur" == *[:@+]* ]] && { COMPREPLY=(); return; }
            compopt -o nospace 2>/dev/null
            mapfile -t COMPREPLY < <(compgen -W "$_hitl_faults" -- "$cur") ;;
        *)
            COMPREPLY=() ;;
    esac
}

# _hitl_is_command PATH WORD: true when WORD is a subcommand of the command path.
_hitl_is_command() {
    local c
    for c in $(_hitl_commands "$1"); do
        [[ "$c" == "$2" ]] && return 0
    done
    return 1
}

_hitl() {
    local cur="${COMP_WORDS[COMP_CWORD]}" path="" word kind option="" i=1 npos=0
    local -a k
    COMPREPLY=()
    # The words before the cursor: subcommands extend the path, options skip their value.
    while (( i < COMP_CWORD )); do
        word="${COMP_WORDS[i]}"
        if [[ "$word" == -* ]]; then
            if [[ "${COMP_WORDS[i+1]:-}" == "=" ]]; then
                i=$((i + 2))  # --option=value, which bash splits at '='
            elif [[ "$word" != *=* ]]; then
                kind="$(_hitl_value "$path" "$word")"
                if [[ "$kind" == optional* ]]; then
                    [[ $((i + 1)) -lt $COMP_CWORD && "${COMP_WORDS[i+1]}" != -* ]] && i=$((i + 1))
                elif [[ -n "$kind" ]]; then
                    i=$((i + 1))
                fi
            fi
        elif _hitl_is_command "$path" "$word"; then
            path="${path:+$path }$word"
            npos=0
        else
            npos=$((npos + 1))
        fi
        i=$((i + 1))
    done

    # The value of an option: after "--option ", "--option=" or "--option=partial".
    local prev="${COMP_WORDS[COMP_CWORD-1]:-}"
    if [[ "$cur" == "=" && "$prev" == -* ]]; then
        option="$prev"
        cur=""
    elif [[ "$prev" == "=" && $COMP_CWORD -ge 2 && "${COMP_WORDS[COMP_CWORD-2]}" == -* ]]; then
        option="${COMP_WORDS[COMP_CWORD-2]}"
    elif [[ "$prev" == -* && "$prev" != *=* && $COMP_CWORD -ge 2 ]]; then
        option="$prev"
    fi
    if [[ -n "$option" ]]; then
        kind="$(_hitl_value "$path" "$option")"
        if [[ "$kind" == optional* && "$cur" != -* ]]; then
            kind="${kind#optional }"
        elif [[ "$kind" == optional* ]]; then
            kind=""
        fi
        if [[ -n "$kind" ]]; then
            read -r -a k <<< "$kind"
            _hitl_complete_value "$cur" "${k[@]}"
            return 0
        fi
    fi

    if [[ "$cur" == -* ]]; then
        mapfile -t COMPREPLY < <(compgen -W "$(_hitl_options "$path")" -- "$cur")
        return 0
    fi
    local commands
    commands="$(_hitl_commands "$path")"
    if [[ -n "$commands" ]]; then
        mapfile -t COMPREPLY < <(compgen -W "$commands" -- "$cur")
        return 0
    fi
    kind="$(_hitl_positional "$path" "$npos")"
    if [[ -n "$kind" ]]; then
        read -r -a k <<< "$kind"
        _hitl_complete_value "$cur" "${k[@]}"
        return 0
    fi
    mapfile -t COMPREPLY < <(compgen -W "$(_hitl_options "$path")" -- "$cur")
    return 0
}

complete -F _hitl hitl
)bash";

}  // namespace

std::string bash_completion(const CommandModel& root, const std::vector<std::string>& message_names,
                            const std::vector<std::string>& fault_names) {
  const auto commands = all_commands(root);
  std::ostringstream out;
  out << "# bash completion for hitl                                            -*- shell-script -*-\n"
         "# Generated by `hitl completion bash` from hitl's command-line model. Do not edit: run\n"
         "# scripts/regen-completions.sh after changing a command or an option.\n"
         "# Install: copy to /usr/share/bash-completion/completions/hitl, or source it from ~/.bashrc.\n\n";

  out << "# MAVLink messages compiled into hitl (for --show, --expect).\n_hitl_messages=";
  std::string names;
  for (const auto& n : message_names) names += (names.empty() ? "" : " ") + n;
  out << shell_quoted(names) << "\n\n";
  std::string faults;
  for (const auto& n : fault_names) faults += (faults.empty() ? "" : " ") + n;
  out << "# The faults hitl injects (for --fault).\n_hitl_faults=" << shell_quoted(faults) << "\n\n";

  out << "# _hitl_commands PATH: the subcommands of a command path ('' is hitl, 'params' is hitl params).\n"
         "_hitl_commands() {\n    case \"$1\" in\n";
  for (const auto* c : commands) {
    if (c->commands.empty()) continue;
    std::string words;
    for (const auto& s : c->commands) words += (words.empty() ? "" : " ") + s.name();
    out << "        " << shell_quoted(join_path(c->path)) << ") echo " << shell_quoted(words) << " ;;\n";
  }
  out << "    esac\n}\n\n";

  out << "# _hitl_options PATH: the options a command path accepts, its parents' included where they fall through.\n"
         "_hitl_options() {\n    case \"$1\" in\n";
  for (const auto* c : commands) {
    std::string words;
    for (const auto* o : accepted_options(root, c->path))
      for (const auto& s : o->spellings()) words += (words.empty() ? "" : " ") + s;
    out << "        " << shell_quoted(join_path(c->path)) << ") echo " << shell_quoted(words) << " ;;\n";
  }
  out << "    esac\n}\n\n";

  // Each option definition once, with every PATH|SPELLING at which it is accepted.
  std::map<const OptionModel*, std::vector<std::string>> where;
  std::vector<const OptionModel*> order;
  for (const auto* c : commands)
    for (const auto* o : accepted_options(root, c->path)) {
      if (value_kind(*o).empty()) continue;
      if (!where.count(o)) order.push_back(o);
      for (const auto& s : o->spellings()) where[o].push_back(shell_quoted(join_path(c->path) + "|" + s));
    }
  out << "# _hitl_value PATH OPTION: how the option's value completes (nothing for a flag): text, choice WORD...,\n"
         "# file [PATTERN], dir, messages, message-rates; \"optional KIND\" when the value may be left out.\n"
         "_hitl_value() {\n    case \"$1|$2\" in\n";
  for (const auto* o : order) {
    std::string patterns;
    for (const auto& p : where[o]) patterns += (patterns.empty() ? "" : "|") + p;
    out << "        " << patterns << ") echo " << shell_quoted(value_kind(*o)) << " ;;\n";
  }
  out << "    esac\n}\n\n";

  out << "# _hitl_positional PATH INDEX: how the INDEX-th positional argument (from 0) completes.\n"
         "_hitl_positional() {\n    case \"$1|$2\" in\n";
  for (const auto* c : commands) {
    const auto positionals = c->positionals();
    for (std::size_t i = 0; i < positionals.size(); ++i) {
      const auto& p = *positionals[i];
      const auto kind = value_kind(p);
      if (kind.empty() || kind == "text") continue;
      const bool last_repeats = p.repeatable && i + 1 == positionals.size();
      out << "        " << shell_quoted(join_path(c->path) + "|") << (last_repeats ? "*" : std::to_string(i)) << ") echo "
          << shell_quoted(kind) << " ;;\n";
    }
  }
  out << "    esac\n}\n";
  out << kWalker;
  return out.str();
}

}  // namespace hitl::cli
