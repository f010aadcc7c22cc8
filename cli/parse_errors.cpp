#include "cli/parse_errors.h"

#include <algorithm>
#include <fstream>

namespace hitl::cli {
namespace {

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

std::vector<CLI::App*> subcommands_of(CLI::App* app) {
  return app->get_subcommands([](CLI::App*) { return true; });
}

CLI::App* subcommand_named(CLI::App* app, const std::string& name) {
  for (auto* sub : subcommands_of(app))
    if (sub->get_name() == name) return sub;
  return nullptr;
}

const CLI::Option* option_in(const std::vector<CLI::App*>& chain, const std::string& name) {
  for (auto* a : chain)
    if (const auto* o = a->get_option_no_throw(name)) return o;
  return nullptr;
}

std::string command_path(const std::vector<CLI::App*>& chain) {
  std::string path;
  for (auto* a : chain) path += (path.empty() ? "" : " ") + a->get_name();
  return path;
}

std::string did_you_mean(const std::optional<std::string>& guess) { return guess ? "; did you mean '" + *guess + "'?" : ""; }

std::string explain_config(CLI::App& app, const std::string& what, const std::string& file) {
  const std::string prefix = "INI was not able to parse ";
  if (what.rfind(prefix, 0) != 0) return {};
  const std::string item = what.substr(prefix.size());
  const auto dot = item.rfind('.');
  const std::string section = dot == std::string::npos ? "" : item.substr(0, dot);
  const std::string key = dot == std::string::npos ? item : item.substr(dot + 1);
  // Where in the file: the line that sets the key (or holds the text TOML could not read).
  int line_no = 0;
  std::ifstream in(file);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    const auto start = line.find_first_not_of(" \t");
    if (start == std::string::npos) continue;
    const std::string rest = line.substr(start);
    if (rest.rfind(key, 0) == 0 && (rest.size() == key.size() || std::string(" \t=").find(rest[key.size()]) != std::string::npos)) {
      line_no = n;
      break;
    }
  }
  const std::string where = (file.empty() ? std::string("--config") : file) + (line_no ? ":" + std::to_string(line_no) : "");
  // The section's command: its options' long names are the keys it takes.
  CLI::App* cmd = &app;
  std::stringstream parts(section);
  for (std::string part; std::getline(parts, part, '.');)
    if (auto* sub = cmd != nullptr ? subcommand_named(cmd, part) : nullptr) cmd = sub;
  std::vector<std::string> keys;
  for (const auto* o : cmd->get_options())
    for (const auto& l : o->get_lnames()) keys.push_back(l);
  if (section.empty() && subcommand_named(&app, key) != nullptr)
    return "hitl: " + where + ": '" + key + "' is not TOML: a section is written [" + key + "] (docs/config.md)";
  return "hitl: " + where + ": unknown key '" + key + "'" + (section.empty() ? "" : " in [" + section + "]") + did_you_mean(closest(key, keys)) +
         " (the file is TOML: key = value under [command] sections; docs/config.md lists every key)";
}

}  // namespace

std::optional<std::string> closest(const std::string& word, const std::vector<std::string>& candidates) {
  std::optional<std::string> best;
  std::size_t best_distance = std::max<std::size_t>(2, word.size() / 3) + 1;
  for (const auto& c : candidates) {
    const std::size_t d = edit_distance(word, c);
    if (d < best_distance) {
      best_distance = d;
      best = c;
    }
  }
  return best;
}

std::string explain_parse_error(CLI::App& app, const CLI::ParseError& error, const std::vector<std::string>& args,
                                const std::string& config_file) {
  const std::string what = error.what();
  if (auto config = explain_config(app, what, config_file); !config.empty()) return config;

  // Number ranges are said plainly where they are checked (cli/number_check.h), not rewritten here.

  // A word that is no command or option of where it was typed.
  std::vector<CLI::App*> chain{&app};
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& t = args[i];
    if (t.size() > 1 && t[0] == '-') {
      const std::string name = t.substr(0, t.find('='));
      const auto* o = option_in(chain, name);
      if (o == nullptr && t.rfind("--", 0) == 0) {
        std::vector<std::string> names;
        for (auto* a : chain)
          for (const auto* opt : a->get_options())
            for (const auto& l : opt->get_lnames()) names.push_back("--" + l);
        return command_path(chain) + ": unknown option '" + name + "'" + did_you_mean(closest(name, names));
      }
      if (o != nullptr && t.find('=') == std::string::npos && o->get_expected_min() > 0) ++i;  // its value
      continue;
    }
    if (auto* sub = subcommand_named(chain.back(), t)) {
      chain.push_back(sub);
      continue;
    }
    const auto subs = subcommands_of(chain.back());
    if (!subs.empty()) {
      std::vector<std::string> names;
      for (auto* s : subs) names.push_back(s->get_name());
      return command_path(chain) + ": unknown command '" + t + "'" + did_you_mean(closest(t, names)) + " (" +
             command_path(chain) + " --help lists them)";
    }
  }
  // No command where one is needed (`hitl`, `hitl params`): the commands there, with what each does.
  if (dynamic_cast<const CLI::RequiredError*>(&error) != nullptr && chain.back()->get_require_subcommand_min() > 0 &&
      chain.back()->get_subcommands().empty()) {
    std::string text = command_path(chain) + ": a command is needed:";
    std::size_t width = 0;
    std::vector<CLI::App*> shown;
    for (auto* sub : subcommands_of(chain.back()))
      if (!sub->get_group().empty()) shown.push_back(sub);  // an empty group hides a command from help
    for (auto* sub : shown) width = std::max(width, sub->get_name().size());
    for (auto* sub : shown) {
      const std::string& name = sub->get_name();
      text += "\n  " + name + std::string(width - name.size() + 2, ' ') + sub->get_description();
    }
    return text + "\n(" + command_path(chain) + " COMMAND --help for its options)";
  }
  // A value its option's check refused: said as the other mistakes are, with the command it was typed for.
  if (dynamic_cast<const CLI::ValidationError*>(&error) != nullptr) return command_path(chain) + ": " + what;
  return {};
}

}  // namespace hitl::cli
