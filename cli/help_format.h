// `--help` for people, from the same command model as the man page: each option's value named as
// argparse names it (--hil-port HIL_PORT, --record FILE.tlog; never CLI11's "UINT:INT in [1 -
// 65535]"), then its description and the man page's notes (what it accepts, its default, what it
// cannot be given with), wrapped to the terminal's width (80 columns when it is not a terminal).
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace hitl::cli {

class HelpFormatter : public CLI::Formatter {
 public:
  HelpFormatter();
  std::string make_option(const CLI::Option* opt, bool is_positional) const override;

 private:
  std::size_t width_;
};

/// Wraps `text` to lines of at most `width` characters (words never cut; existing newlines kept).
std::string wrap_words(const std::string& text, std::size_t width);

}  // namespace hitl::cli
