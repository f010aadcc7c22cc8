// Rolling graphs drawn with characters, as btop draws them: a series of samples (oldest first, NaN
// where there was none) becomes a grid of cells, the newest sample at the right edge. Braille
// (U+2800..U+28FF) packs 2x4 dots in a cell; the ASCII fallback one mark a cell at three heights
// ('_' '-' '\''), for terminals whose locale is not UTF-8 or when HITL_GRAPH_SYMBOL=ascii.
// Pure functions: the screen only writes the cells they return.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace hitl::tui {

enum class GraphSymbols { Braille, Ascii };

inline constexpr char32_t kBrailleBase = 0x2800;  ///< the blank braille cell; + dot bits

/// The braille bit of dot (dx 0..1 from the left, dy 0..3 from the top) of a cell.
unsigned braille_bit(int dx, int dy);

/// The samples averaged into `columns` columns over a window `capacity` samples long, right-aligned
/// (a window not yet full leaves its left columns NaN). Non-finite samples are skipped.
std::vector<double> resample(const std::vector<double>& samples, std::size_t capacity, int columns);

/// One series as `height` rows of `width` cells (top row first), lo at the bottom edge and hi at
/// the top (values outside are clamped to the edge). Cells with nothing are U' '. Braille joins
/// neighbouring samples with vertical dots so a steep change reads as a line.
std::vector<std::u32string> plot(const std::vector<double>& samples, std::size_t capacity, int width, int height, double lo,
                                 double hi, GraphSymbols symbols);

/// `top` drawn over `bottom` (same size): braille cells merge their dots, other cells of `top` win
/// where they are not blank.
void overlay(std::vector<std::u32string>& bottom, const std::vector<std::u32string>& top);

/// The graph's range for its finite samples: [min, max] widened to at least `min_span` around them
/// (flat series sit mid-height); {0, min_span} when there are none.
std::pair<double, double> range_of(const std::vector<std::vector<double>>& series, double min_span);

/// How the dashboard draws graphs: HITL_GRAPH_SYMBOL ("braille" or "ascii") when set to one of
/// them; else braille when the locale's character set is UTF-8 and TERM is not "linux" (the
/// Linux console's font has no braille; btop turns to its tty mode there too).
GraphSymbols choose_graph_symbols(const char* graph_symbol_env, bool utf8_locale, const char* term);

/// A cell as UTF-8.
std::string utf8(char32_t ch);

}  // namespace hitl::tui
