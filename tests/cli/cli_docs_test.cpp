// The command model read from a small CLI11 app with every construct hitl's commands use, and what
// the generators make of it: a change in how CLI11 describes options shows up here first.
#include <gtest/gtest.h>

#include <cctype>
#include <map>
#include <optional>

#include "cli/command_model.h"
#include "cli/completions.h"
#include "cli/config_reference.h"
#include "cli/help_format.h"
#include "cli/man_page.h"
#include "cli/option_words.h"
#include "cli/value_types.h"

namespace hitl::cli {
namespace {

struct SmallApp {
  CLI::App app{"demo: a small app", "hitl"};
  bool json = false;
  int verbose = 0;
  std::string ip = "127.0.0.1", protocol = "2.0", trajectory, sitl, name;
  double lockstep_timeout_s = 0.5, tolerance_pct = 5.0;
  int mode = 0;
  uint16_t hil_port = 14560;
  std::optional<uint16_t> port;
  std::vector<std::string> show;
  std::string expect;

  SmallApp() {
    app.require_subcommand(1);
    app.fallthrough();
    app.add_flag("--json", json, "Machine output")->group("Output");
    app.add_flag("-v,--verbose", verbose, "More detail; -vv more")->group("Output");
    app.set_config("--config", "", "Read options from a TOML file")->type_name(value_type::kConfigFile)->group("Config");

    auto* sim = app.add_subcommand("sim", "Simulate the x500 (and more)");
    sim->add_option("-i,--target-ip,--mavlink-addr", ip, "The board's IP")->capture_default_str()->group("Board link");
    sim->add_option("--hil-port", hil_port, "The board's HIL port")->check(CLI::Range(1, 65535))->group("Board link");
    sim->add_option("--protocol-version", protocol, "MAVLink protocol version")->check(CLI::IsMember({"1.0", "2.0"}));
    sim->add_option("-t,--trajectory", trajectory, "Fly this trajectory file")->check(CLI::ExistingFile)->type_name("FILE.json");
    sim->add_option("--lockstep-timeout", lockstep_timeout_s, "How long lockstep waits for an answer, s")
        ->check(CLI::PositiveNumber);
    sim->add_option("--px4-sitl", sitl, "Serve PX4 SITL")->expected(0, 1)->type_name("[tcp:4560|udp:PORT]");
    const std::map<std::string, int> modes{{"velocity", 0}, {"attitude", 1}};
    sim->add_option("--trajectory-mode", mode, "-t's sticks")->transform(CLI::CheckedTransformer(modes));

    auto* inspect = app.add_subcommand("inspect", "Decode and measure MAVLink");
    auto* source = inspect->add_option_group("Source", "exactly one");
    source->add_option("--port", port, "Listen on this UDP port")->check(CLI::Range(1, 65535));
    inspect->add_option("--show", show, "Print these messages")->delimiter(',')->type_name(value_type::kMessageList);
    inspect->add_option("--expect", expect, "Rates")->type_name(value_type::kMessageRateList);
    inspect->add_option("--tolerance", tolerance_pct, "Accepted deviation, percent")->type_name("PCT");

    auto* params = app.add_subcommand("params", "PX4 parameters");
    params->require_subcommand(1);
    params->add_option("--timeout", lockstep_timeout_s, "Seconds to wait for the autopilot")->group("Connection");
    params->add_subcommand("get", "Print one parameter")->add_option("NAME", name, "The parameter")->required();
    params->add_subcommand("export", "Save every parameter")->add_option("FILE", name)->required();

    app.add_subcommand("secret", "A hidden command")->group("");
  }
};

const OptionModel& option(const CommandModel& c, const std::string& spelling) {
  for (const auto& o : c.options) {
    const auto s = o.spellings();
    if (std::find(s.begin(), s.end(), spelling) != s.end() || o.positional == spelling) return o;
  }
  throw std::runtime_error("no option " + spelling + " in " + c.full_name());
}

TEST(CommandModel, ReadsCommandsAndLeavesHiddenOnesOut) {
  SmallApp s;
  const auto root = read_command_model(s.app);
  ASSERT_EQ(root.commands.size(), 3u);
  EXPECT_EQ(root.commands[0].name(), "sim");
  EXPECT_EQ(root.commands[1].name(), "inspect");
  EXPECT_EQ(root.commands[2].name(), "params");
  EXPECT_TRUE(root.needs_command);
  EXPECT_FALSE(root.fallthrough);  // nothing above hitl itself
  const auto* get = find_command(root, {"params", "get"});
  ASSERT_NE(get, nullptr);
  EXPECT_EQ(get->full_name(), "hitl params get");
  EXPECT_TRUE(get->fallthrough);  // inherited from the root's app.fallthrough()
  EXPECT_EQ(find_command(root, {"secret"}), nullptr);
  EXPECT_EQ(all_commands(root).size(), 6u);
}

TEST(CommandModel, ReadsEachKindOfOption) {
  SmallApp s;
  const auto root = read_command_model(s.app);
  const auto& sim = *find_command(root, {"sim"});

  const auto& ip = option(sim, "-i");
  EXPECT_EQ(ip.long_names, (std::vector<std::string>{"target-ip", "mavlink-addr"}));
  EXPECT_EQ(ip.config_key(), "target-ip");
  EXPECT_EQ(ip.default_value, "127.0.0.1");
  EXPECT_EQ(ip.kind, ValueKind::Text);
  EXPECT_EQ(ip.group, "Board link");

  const auto& hil = option(sim, "--hil-port");
  EXPECT_EQ(hil.type_name, "UINT");
  EXPECT_EQ(hil.default_value, "14560");  // captured although the command did not ask for it
  EXPECT_EQ(option_constraints(hil), "1 to 65535");

  const auto& protocol = option(sim, "--protocol-version");
  EXPECT_EQ(protocol.kind, ValueKind::Choice);
  EXPECT_EQ(protocol.choices, (std::vector<std::string>{"1.0", "2.0"}));
  EXPECT_EQ(protocol.type_name, "TEXT");

  const auto& t = option(sim, "--trajectory");
  EXPECT_EQ(t.kind, ValueKind::File);
  EXPECT_EQ(t.file_pattern, "*.json");
  EXPECT_EQ(t.type_name, "FILE.json");

  const auto& lockstep = option(sim, "--lockstep-timeout");
  EXPECT_EQ(lockstep.default_value, "0.5");
  EXPECT_EQ(option_unit(lockstep), "s");
  EXPECT_EQ(option_constraints(lockstep), "greater than 0");

  const auto& sitl = option(sim, "--px4-sitl");
  EXPECT_TRUE(sitl.optional_value());
  EXPECT_EQ(sitl.type_name, "[tcp:4560|udp:PORT]");

  const auto& mode = option(sim, "--trajectory-mode");
  EXPECT_EQ(mode.kind, ValueKind::Choice);
  EXPECT_EQ(mode.choices, (std::vector<std::string>{"attitude", "velocity"}));

  const auto& inspect = *find_command(root, {"inspect"});
  const auto& port = option(inspect, "--port");
  EXPECT_EQ(port.group, "Source");  // from its option group
  EXPECT_EQ(port.default_value, "");
  const auto& show = option(inspect, "--show");
  EXPECT_EQ(show.kind, ValueKind::MessageList);
  EXPECT_TRUE(show.repeatable);
  EXPECT_EQ(show.delimiter, ',');
  EXPECT_EQ(show.default_value, "");
  EXPECT_EQ(option(inspect, "--expect").kind, ValueKind::MessageRates);
  EXPECT_EQ(option_unit(option(inspect, "--tolerance")), "%");

  const auto& config = option(root, "--config");
  EXPECT_EQ(config.kind, ValueKind::File);
  EXPECT_EQ(config.file_pattern, "*.toml");
  EXPECT_FALSE(config.configurable);
  const auto& verbose = option(root, "-v");
  EXPECT_TRUE(verbose.is_flag());
  EXPECT_TRUE(verbose.repeatable);
  EXPECT_TRUE(option(root, "--help").help);
  EXPECT_FALSE(option(root, "--help").configurable);

  const auto& name = option(*find_command(root, {"params", "get"}), "NAME");
  EXPECT_TRUE(name.required);
  EXPECT_EQ(name.kind, ValueKind::Text);
  EXPECT_EQ(option(*find_command(root, {"params", "export"}), "FILE").kind, ValueKind::File);
}

// Issue 36: --help showed CLI11's type names ("UINT:INT in [1 - 65535]=14560 Excludes: --adb").
// The value is named as argparse names it, and what it accepts, its default and what it excludes
// are sentences, as in the man page.
TEST(HelpText, NamesValuesAsArgparseAndSaysWhatTheyAccept) {
  SmallApp s;
  const auto model = read_command_model(s.app);
  const auto& sim = *find_command(model, {"sim"});
  EXPECT_EQ(option_metavar(option(sim, "--hil-port")), "HIL_PORT");
  EXPECT_EQ(option_metavar(option(sim, "-i")), "TARGET_IP");
  EXPECT_EQ(option_metavar(option(sim, "--trajectory")), "FILE.json");
  EXPECT_EQ(option_metavar(option(sim, "--protocol-version")), "1.0|2.0");
  EXPECT_EQ(option_metavar(option(sim, "--trajectory-mode")), "attitude|velocity");
  EXPECT_EQ(option_value_tag(option(sim, "--px4-sitl")), "[tcp:4560|udp:PORT]");  // bracketed once
  EXPECT_EQ(option_accepts(option(sim, "--hil-port")), "an integer, 1 to 65535");
  EXPECT_EQ(option_accepts(option(sim, "--lockstep-timeout")), "a number, greater than 0");
  const auto notes = option_notes(option(sim, "--hil-port"));
  EXPECT_EQ(notes, (std::vector<std::string>{"Accepts an integer, 1 to 65535.", "Default: 14560."}));

  SmallApp h;
  auto* sim_app = h.app.get_subcommand("sim");
  sim_app->get_option("--px4-sitl")->excludes(sim_app->get_option("--hil-port"));
  sim_app->get_option("--hil-port")->capture_default_str();  // as hitl's options do
  HelpFormatter f;
  std::string text;  // wrapped to the terminal: compared with single spaces
  for (char c : f.make_option(sim_app->get_option("--hil-port"), false))
    if (!std::isspace(static_cast<unsigned char>(c)) || (!text.empty() && text.back() != ' ')) text += std::isspace(static_cast<unsigned char>(c)) ? ' ' : c;
  EXPECT_NE(text.find("--hil-port HIL_PORT"), std::string::npos) << text;
  EXPECT_NE(text.find("The board's HIL port. Accepts an integer, 1 to 65535. Default: 14560."), std::string::npos) << text;
  EXPECT_NE(text.find("Not with --px4-sitl."), std::string::npos) << text;
  for (const char* internal : {"UINT", "INT in", "Excludes:", "=14560"}) EXPECT_EQ(text.find(internal), std::string::npos) << text;
}

TEST(CommandModel, AcceptedOptionsFollowFallthroughAndDeduplicateHelp) {
  SmallApp s;
  const auto root = read_command_model(s.app);
  std::vector<std::string> spellings;
  for (const auto* o : accepted_options(root, {"params", "get"}))
    for (const auto& sp : o->spellings()) spellings.push_back(sp);
  EXPECT_EQ(std::count(spellings.begin(), spellings.end(), "--help"), 1);
  EXPECT_NE(std::find(spellings.begin(), spellings.end(), "--timeout"), spellings.end());  // params'
  EXPECT_NE(std::find(spellings.begin(), spellings.end(), "--json"), spellings.end());     // hitl's
  EXPECT_EQ(std::find(spellings.begin(), spellings.end(), "NAME"), spellings.end());      // positionals apart
}

TEST(CommandModel, SummaryCutsToAPhrase) {
  EXPECT_EQ(summary("Simulate the x500 (and more)"), "Simulate the x500");
  EXPECT_EQ(summary("Run one command and print its output; more"), "Run one command and print its output");
  EXPECT_EQ(summary("Short (kept whole)"), "Short (kept whole)");  // cutting would leave too little
  const auto long_text = summary(std::string(200, 'a') + " b", 50);
  EXPECT_EQ(long_text.size(), 53u);
}

TEST(ManPage, EscapesRoff) {
  EXPECT_EQ(roff_escape("--port"), "\\-\\-port");
  EXPECT_EQ(roff_escape(".hidden\n'quote"), "\\&.hidden\n\\&'quote");
  EXPECT_EQ(roff_escape("a\\b"), "a\\eb");
  EXPECT_EQ(roff_escape("\xC2\xB1 0.3 m"), "\\[u00B1] 0.3 m");
  EXPECT_EQ(roff_escape("\xE2\x86\x92"), "\\[u2192]");
  EXPECT_EQ(roff_escape("\xFF"), "\\[uFFFD]");  // not UTF-8
}

TEST(ManPage, FillsTheTemplate) {
  SmallApp s;
  const auto root = read_command_model(s.app);
  const auto page = man_page(root, ".TH HITL 1 2025-01-01 \"hitl @VERSION@\"\n.SH GLOBAL\n.\\\" @GLOBAL_OPTIONS@\n.SH COMMANDS\n.\\\" @COMMANDS@\n", "9.9.9");
  EXPECT_NE(page.find("\"hitl 9.9.9\""), std::string::npos);
  EXPECT_EQ(page.find("@COMMANDS@"), std::string::npos);
  EXPECT_NE(page.find("\\fB\\-\\-json\\fR"), std::string::npos);
  EXPECT_NE(page.find(".SS \"hitl params get\""), std::string::npos);
  EXPECT_NE(page.find("Default: 0.5 s."), std::string::npos);
  EXPECT_NE(page.find("Accepts one of 1.0, 2.0."), std::string::npos);
  EXPECT_NE(page.find("The options of \\fBhitl params\\fR apply here too."), std::string::npos);
  EXPECT_EQ(page.find("secret"), std::string::npos);
}

TEST(ConfigReference, ListsEveryConfigurableOptionPerSection) {
  SmallApp s;
  const auto root = read_command_model(s.app);
  const auto md = config_reference(root);
  EXPECT_NE(md.find("## `[sim]`: `hitl sim`"), std::string::npos);
  EXPECT_NE(md.find("## `[params.get]`: `hitl params get`"), std::string::npos);
  EXPECT_NE(md.find("| `target-ip` (`mavlink-addr`, flag `-i`) | string | `\"127.0.0.1\"` |  |"), std::string::npos) << md;
  EXPECT_NE(md.find("| `lockstep-timeout` | number: greater than 0 | `0.5` | s |"), std::string::npos) << md;
  EXPECT_NE(md.find("| `tolerance` | number | `5` | % |"), std::string::npos) << md;
  EXPECT_EQ(md.find("`config`"), std::string::npos);  // --config is not a key
  EXPECT_EQ(md.find("`help`"), std::string::npos);
}

TEST(Completions, EveryShellGetsEveryCommandAndOption) {
  SmallApp s;
  const auto root = read_command_model(s.app);
  const std::vector<std::string> messages{"ATTITUDE", "HEARTBEAT"};
  for (const auto& script : {bash_completion(root, messages), zsh_completion(root, messages), fish_completion(root, messages)}) {
    for (const char* word : {"sim", "inspect", "params", "get", "export", "--target-ip", "--mavlink-addr", "--protocol-version",
                             "--trajectory-mode", "attitude", "--port", "HEARTBEAT", "ATTITUDE"})
      EXPECT_NE(script.find(word), std::string::npos) << word << " missing from:\n" << script;
    EXPECT_EQ(script.find("secret"), std::string::npos);
  }
}

}  // namespace
}  // namespace hitl::cli
