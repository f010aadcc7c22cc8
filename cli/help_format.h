// `--help` for people: value types without the parser's internals ("1..65535", not
// "UINT:INT in [1 - 65535]"; "attitude|velocity", not "ENUM:value in {attitude->1,...}"), and
// descriptions wrapped to the terminal's width (80 columns when it is not a terminal).
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace hitl::cli {

class HelpFormatter : public CLI::Formatter {
 public:
  HelpFormatter();
  std::string make_option(const CLI::Option* opt, bool is_positional) const override;
  std::string make_option_opts(const CLI::Option* opt) const override;

 private:
  std::size_t width_;
};

/// "UINT:INT in [1 - 65535]=14560 Excludes: --adb" as "UINT 1..65535 =14560 Excludes: --adb".
std::string plain_type_text(const std::string& opts);

/// Wraps `text` to lines of at most `width` characters (words never cut; existing newlines kept).
std::string wrap_words(const std::string& text, std::size_t width);

}  // namespace hitl::cli
