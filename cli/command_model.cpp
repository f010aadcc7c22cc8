#include "cli/command_model.h"

#include <algorithm>
#include <set>

#include "cli/value_types.h"

namespace hitl::cli {
namespace {

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t");
  if (a == std::string::npos) return {};
  return s.substr(a, s.find_last_not_of(" \t") - a + 1);
}

/// The validators' descriptions. CLI11 2.1 lists validators only by index, ending in OptionNotFound.
std::vector<std::string> validator_descriptions(CLI::Option& o) {
  std::vector<std::string> out;
  for (int i = 0;; ++i) {
    CLI::Validator* v = nullptr;
    try {
      v = o.get_validator(i);
    } catch (const CLI::OptionNotFound&) {
      break;
    }
    if (v->get_active() && !v->get_description().empty()) out.push_back(v->get_description());
  }
  return out;
}

/// The words of a set CLI11 describes as "{a,b}" (IsMember) or "value in {a->1,b->0} OR {1,0}"
/// (CheckedTransformer): what a user types is the part before "->" in the first braces.
std::vector<std::string> choices_from(const std::string& description) {
  const auto open = description.find('{');
  const auto close = description.find('}', open == std::string::npos ? 0 : open);
  if (open == std::string::npos || close == std::string::npos) return {};
  std::vector<std::string> out;
  std::string item;
  const std::string inside = description.substr(open + 1, close - open - 1);
  for (std::size_t i = 0; i <= inside.size(); ++i) {
    if (i == inside.size() || inside[i] == ',') {
      const auto arrow = item.find("->");
      const auto word = trim(arrow == std::string::npos ? item : item.substr(0, arrow));
      if (!word.empty()) out.push_back(word);
      item.clear();
    } else {
      item += inside[i];
    }
  }
  return out;
}

void classify(OptionModel& m) {
  if (m.is_flag()) {
    m.kind = ValueKind::None;
    return;
  }
  const std::string file_prefix = value_type::kFilePrefix;
  const bool file_type = m.type_name == file_prefix || starts_with(m.type_name, file_prefix + ".");
  const bool file_check = std::any_of(m.checks.begin(), m.checks.end(), [](const std::string& c) {
    return c == "FILE" || c == "PATH(existing)" || c == "PATH(non-existing)";
  });
  if (m.type_name == value_type::kMessageList) {
    m.kind = ValueKind::MessageList;
  } else if (m.type_name == value_type::kMessageRateList) {
    m.kind = ValueKind::MessageRates;
  } else if (m.type_name == value_type::kFaultSpec) {
    m.kind = ValueKind::FaultSpec;
  } else if (file_type || file_check || m.positional == file_prefix) {
    m.kind = ValueKind::File;
    if (file_type && m.type_name.size() > file_prefix.size()) m.file_pattern = "*" + m.type_name.substr(file_prefix.size());
  } else if (std::find(m.checks.begin(), m.checks.end(), "DIR") != m.checks.end()) {
    m.kind = ValueKind::Directory;
  } else {
    for (const auto& c : m.checks)
      if (auto words = choices_from(c); !words.empty()) {
        m.kind = ValueKind::Choice;
        m.choices = std::move(words);
        return;
      }
    if (m.type_name == "BOOLEAN") {
      m.kind = ValueKind::Choice;
      m.choices = {"true", "false"};
      return;
    }
    m.kind = ValueKind::Text;
  }
}

OptionModel read_option(CLI::Option& o, const std::string& group, bool help, bool capture_default = true) {
  OptionModel m;
  m.long_names = o.get_lnames();
  m.short_names = o.get_snames();
  if (!o.nonpositional()) m.positional = o.get_name();
  m.description = o.get_description();
  m.group = group;
  m.checks = validator_descriptions(o);
  m.type_name = o.get_type_name();
  std::string suffix;
  for (const auto& c : m.checks) suffix += ":" + c;
  if (!suffix.empty() && m.type_name.size() >= suffix.size() &&
      m.type_name.compare(m.type_name.size() - suffix.size(), suffix.size(), suffix) == 0)
    m.type_name.erase(m.type_name.size() - suffix.size());
  if (capture_default) o.capture_default_str();
  for (const CLI::Option* other : o.get_excludes()) {
    const auto names = other->get_lnames();
    m.excludes.push_back(names.empty() ? other->get_name() : "--" + names.front());
  }
  std::sort(m.excludes.begin(), m.excludes.end());  // CLI11 keeps them by address
  m.default_value = o.get_default_str();
  if (m.default_value == "[]") m.default_value.clear();  // an empty list
  m.values_min = o.get_expected_min() > 0 ? 1 : 0;
  m.values_max = o.get_expected_max() > 0 ? 1 : 0;
  const auto policy = o.get_multi_option_policy();
  m.repeatable = policy == CLI::MultiOptionPolicy::TakeAll || policy == CLI::MultiOptionPolicy::Join ||
                 o.get_items_expected_max() > 1;
  m.delimiter = o.get_delimiter();
  m.required = o.get_required();
  m.configurable = o.get_configurable() && !help;
  m.help = help;
  classify(m);
  return m;
}

/// The options of `app` and of its option groups (nameless subcommands), hidden ones left out.
void read_options(CLI::App& app, const std::string& group_name, std::vector<OptionModel>& out) {
  const CLI::Option* help_ptr = app.get_help_ptr();
  const CLI::Option* help_all_ptr = app.get_help_all_ptr();
  const CLI::Option* version_ptr = app.get_version_ptr();
  const bool option_group = app.get_name().empty() && app.get_parent() != nullptr;
  for (CLI::Option* o : app.get_options()) {
    if (o->get_group().empty()) continue;  // hidden
    const bool help = o == help_ptr || o == help_all_ptr || o == version_ptr;
    if (option_group && help) continue;  // an option group's copy of its parent's --help
    const std::string group = (option_group && o->get_group() == "Options") ? group_name : o->get_group();
    out.push_back(read_option(*o, group, help));
  }
  for (CLI::App* sub : app.get_subcommands([](CLI::App* a) { return a->get_name().empty(); }))
    if (!sub->get_group().empty() && !sub->get_disabled()) read_options(*sub, sub->get_group(), out);
}

}  // namespace

OptionModel read_option_model(const CLI::Option& option) {
  // CLI11 hands validators out only through non-const calls; nothing here changes the option.
  return read_option(const_cast<CLI::Option&>(option), option.get_group(), false, false);
}

namespace {

CommandModel read_command(CLI::App& app, std::vector<std::string> path) {
  CommandModel c;
  c.path = std::move(path);
  c.description = app.get_description();
  c.footer = app.get_footer();
  c.fallthrough = app.get_fallthrough() && app.get_parent() != nullptr;
  c.needs_command = app.get_require_subcommand_min() > 0;
  read_options(app, "Options", c.options);
  for (CLI::App* sub : app.get_subcommands([](CLI::App* a) { return !a->get_name().empty(); })) {
    if (sub->get_group().empty() || sub->get_disabled()) continue;  // hidden
    auto sub_path = c.path;
    sub_path.push_back(sub->get_name());
    c.commands.push_back(read_command(*sub, std::move(sub_path)));
  }
  return c;
}

void collect(const CommandModel& c, std::vector<const CommandModel*>& out) {
  out.push_back(&c);
  for (const auto& sub : c.commands) collect(sub, out);
}

}  // namespace

std::vector<std::string> OptionModel::spellings() const {
  std::vector<std::string> out;
  for (const auto& s : short_names) out.push_back("-" + s);
  for (const auto& l : long_names) out.push_back("--" + l);
  return out;
}

std::string OptionModel::config_key() const { return long_names.empty() ? positional : long_names.front(); }

std::string CommandModel::full_name(const std::string& program) const {
  std::string out = program;
  for (const auto& p : path) out += " " + p;
  return out;
}

std::vector<const OptionModel*> CommandModel::positionals() const {
  std::vector<const OptionModel*> out;
  for (const auto& o : options)
    if (!o.positional.empty()) out.push_back(&o);
  return out;
}

CommandModel read_command_model(CLI::App& app) { return read_command(app, {}); }

std::string summary(const std::string& description, std::size_t max_chars) {
  std::string s;
  for (char ch : description) s += (ch == '\n' || ch == '\t') ? ' ' : ch;
  for (const char* cut : {"; ", " ("}) {
    const auto at = s.find(cut);
    if (at != std::string::npos && at >= 12) s.erase(at);
  }
  if (s.size() > max_chars) {
    const auto space = s.rfind(' ', max_chars);
    s.erase(space == std::string::npos || space < max_chars / 2 ? max_chars : space);
    s += "...";
  }
  return trim(s);
}

std::vector<const CommandModel*> all_commands(const CommandModel& root) {
  std::vector<const CommandModel*> out;
  collect(root, out);
  return out;
}

const CommandModel* find_command(const CommandModel& root, const std::vector<std::string>& path) {
  const CommandModel* c = &root;
  for (const auto& name : path) {
    const auto it = std::find_if(c->commands.begin(), c->commands.end(), [&](const CommandModel& s) { return s.name() == name; });
    if (it == c->commands.end()) return nullptr;
    c = &*it;
  }
  return c;
}

std::vector<const OptionModel*> accepted_options(const CommandModel& root, const std::vector<std::string>& path) {
  std::vector<const OptionModel*> out;
  std::set<std::string> seen;
  auto p = path;
  while (true) {
    const CommandModel* c = find_command(root, p);
    if (c == nullptr) break;
    for (const auto& o : c->options) {
      if (!o.positional.empty()) continue;
      const auto names = o.spellings();
      if (std::any_of(names.begin(), names.end(), [&](const std::string& n) { return seen.count(n) > 0; })) continue;
      seen.insert(names.begin(), names.end());
      out.push_back(&o);
    }
    if (p.empty() || !c->fallthrough) break;
    p.pop_back();
  }
  return out;
}

}  // namespace hitl::cli
