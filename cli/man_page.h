// The man page docs/hitl.1: the hand-written roff of docs/man/hitl.1.in (compiled in) with the
// global options and one section per command generated from the command model.
#pragma once

#include <string>

#include "cli/command_model.h"

namespace hitl::cli {

/// `template_roff` holds the lines ".\" @GLOBAL_OPTIONS@" and ".\" @COMMANDS@" where the generated
/// sections go, and "@VERSION@" where the version goes.
std::string man_page(const CommandModel& root, const std::string& template_roff, const std::string& version);

/// Text for roff: backslashes, leading dots and quotes, hyphens and non-ASCII characters escaped.
std::string roff_escape(const std::string& text);

/// The man page template (docs/man/hitl.1.in), compiled in.
extern const char* const kManPageTemplate;

}  // namespace hitl::cli
