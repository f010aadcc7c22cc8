#include "base/common/bounded_read.h"
#include "cli/common_options.h"

#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <iostream>
#include <sstream>

#include "cli/value_types.h"
#include "engine/mavlink/dialect_xml.h"

namespace hitl::cli {

namespace {

/// CLI11's TOML reader with a size cap: `--config /dev/zero` is a named error, not a 2 GB read.
class BoundedConfigToml : public CLI::ConfigTOML {
 public:
  explicit BoundedConfigToml(const CLI::App& app) : app_(app) {}
  std::vector<CLI::ConfigItem> from_config(std::istream& input) const override {
    std::string text(kMaxConfigFileBytes + 1, '\0');
    input.read(text.data(), static_cast<std::streamsize>(text.size()));
    text.resize(static_cast<std::size_t>(input.gcount()));
    if (text.size() > kMaxConfigFileBytes) {
      const auto* option = app_.get_config_ptr();
      const auto files = option != nullptr ? option->as<std::vector<std::string>>() : std::vector<std::string>{};
      const std::string name = files.empty() ? "" : " '" + files.back() + "'";
      throw CLI::FileError("--config" + name + " is larger than " + byte_size_text(kMaxConfigFileBytes) +
                           ", the limit for a configuration file (an endless file such as /dev/zero?)");
    }
    std::istringstream bounded(text);
    return CLI::ConfigTOML::from_config(bounded);
  }

 private:
  const CLI::App& app_;
};

}  // namespace

void add_global_options(CLI::App& app, GlobalOptions& options) {
  app.add_flag("--json", options.json, "Machine output: one JSON object per line, a final summary object last")
      ->group("Output");
  app.add_flag("-v,--verbose", options.verbosity, "More detail on stderr: new senders and message ids as they appear; -vv every frame")->group("Output");
  app.add_flag("-q,--quiet", options.quiet, "Print results only, no progress")->group("Output");
  app.add_option("--dialect", options.dialects,
                 "MAVLink XML to load at run time (with its includes), e.g. ardupilotmega.xml; also "
                 "$HITL_MAVLINK_DIALECT (':'-separated)")
      ->group("MAVLink")
      ->type_name("FILE.xml");
  app.set_config("--config", "", "Read options from a TOML file ([inspect] port = 14570, ...; docs/config.md)")
      ->type_name(value_type::kConfigFile)
      ->group("Config");
  app.config_formatter(std::make_shared<BoundedConfigToml>(app));
  app.allow_config_extras(false);  // a misspelt key is an error naming it, not silently ignored
}

Expected<mavlink::MessageSet> load_messages(const GlobalOptions& options) {
  auto set = mavlink::MessageSet::compiled();
  std::vector<std::string> files;
  if (const char* env = std::getenv(mavlink::kDialectEnvVar); env != nullptr && *env != '\0') {
    std::stringstream ss(env);
    std::string item;
    while (std::getline(ss, item, ':'))
      if (!item.empty()) files.push_back(item);
  }
  files.insert(files.end(), options.dialects.begin(), options.dialects.end());
  for (const auto& file : files) {
    auto info = mavlink::load_dialect(file, set);
    if (!info) return info.error().prefixed("--dialect: ");
  }
  return set;
}

void print_json_line(const nlohmann::json& object) {
  std::cout << object.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) << '\n' << std::flush;
}

void log_info(const GlobalOptions& options, const std::string& line) {
  if (!options.quiet) std::cerr << line << '\n';
}

void log_error(const std::string& command, const std::string& message) {
  std::cerr << "hitl " << command << ": " << message << '\n';
}

int log_error(const std::string& command, const Error& error) {
  log_error(command, error.message);
  return exit_code(error);
}

namespace {
std::atomic<bool>& stop_storage() {
  static std::atomic<bool> stop{false};
  return stop;
}
extern "C" void hitl_cli_on_stop_signal(int sig) {
  stop_storage().store(true);
  std::signal(sig, SIG_DFL);  // a second Ctrl-C ends the process at once
}
}  // namespace

const std::atomic<bool>& stop_flag_on_signals() {
  struct sigaction sa {};
  sa.sa_handler = hitl_cli_on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  return stop_storage();
}

bool stdout_is_tty() { return ::isatty(STDOUT_FILENO) == 1; }

bool background_job_of_terminal() {
  if (::isatty(STDERR_FILENO) != 1) return false;
  const pid_t foreground = ::tcgetpgrp(STDERR_FILENO);
  return foreground > 0 && foreground != ::getpgrp();
}

}  // namespace hitl::cli
