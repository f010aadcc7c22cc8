// MAVLink's fixed-size text fields (STATUSTEXT.text, PARAM_*.param_id, NAMED_VALUE_*.name): NUL-
// terminated when shorter than the field, no NUL when full. Written and read here, once.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <string>
#include <string_view>

namespace hitl::mavlink {

/// Fills `field` with `text`, cut to the field's size, the rest NUL.
template <std::size_t N>
void set_text(std::array<char, N>& field, std::string_view text) {
  field.fill('\0');
  std::copy_n(text.begin(), std::min(text.size(), N), field.begin());
}

/// The text up to the first NUL or the field's end.
template <std::size_t N>
std::string text_of(const std::array<char, N>& field) {
  const auto end = std::find(field.begin(), field.end(), '\0');
  return std::string(field.begin(), end);
}

}  // namespace hitl::mavlink
