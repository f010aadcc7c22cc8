// The small pieces every panel draws with: clipped text, bars, health styles, number formats.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/telemetry/health.h"
#include "tui/dashboard_model.h"
#include "tui/screen.h"

namespace hitl::tui {

/// Text at (x, y) inside `clip` only: cut at its right edge, nothing outside its rows.
void put(Screen& screen, const Rect& clip, int x, int y, std::string_view text, Style style = {});

/// `text` cut or padded with blanks to exactly `width` characters.
std::string fit(std::string_view text, int width);
/// Right-aligned in `width` (cut from the left when longer).
std::string right(std::string_view text, int width);
/// Words wrapped to lines of at most `width` characters (long words are cut).
std::vector<std::string> wrap(std::string_view text, int width);

/// `width` cells: '#' for the filled fraction (0..1, clamped), '-' for the rest; '?' when not
/// finite, so a NaN from the network never looks like a value.
std::string bar(double fraction, int width);

/// printf into a string.
std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
/// A number with `decimals`, or "n/a" when absent or not finite.
std::string number(std::optional<double> value, int decimals);
/// A rate: "249.9" below 1000, "1250" above.
std::string rate(double hz);

/// The style of a health grade: Good green, Degraded yellow, Bad red (bold).
Style health_style(telemetry::Health health);
/// A message's colour by its severity (info plain, notice accent, warning yellow, error red).
Style severity_style(Severity severity);

}  // namespace hitl::tui
