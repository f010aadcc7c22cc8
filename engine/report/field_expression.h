// `hitl report --plot`: any MAVLink field, as MAVExplorer plots them (docs/report.md "Any field").
// A --plot value is one plot: series separated by commas, each an expression of one message's
// fields, checked against the messages hitl's codec knows (base/mavlink's generated layouts):
//
//   series   := expr
//   expr     := term (('+' | '-') term)*
//   term     := unary (('*' | '/') unary)*
//   unary    := ('-' | '+') unary | primary
//   primary  := NUMBER | '(' expr ')' | FUNCTION '(' expr ')' | MESSAGE '.' field ['[' INDEX ']']
//
// FUNCTION is one of degrees, radians, abs, sqrt. An array field takes its element by index
// (HIL_ACTUATOR_CONTROLS.controls[0]); a text field (char[]) is refused. Written by hand (a
// recursive descent): muparser (Debian's libmuparser-dev) takes names of letters, digits and '_' and
// no index, reports positions in its own rewritten text and knows nothing of MAVLink's fields, which
// must be checked before a log is read; this grammar is five rules.
//
// A --plot value is outside input: its length, its series, the nodes of a series and their nesting
// are bounded (FieldPlotLimits); every refusal says where (1-based character of the value) and why.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "base/common/expected.h"
#include "base/mavlink/message_set.h"

namespace hitl::report {

struct FieldPlotLimits {
  std::size_t max_chars = 1000;   ///< of one --plot value
  std::size_t max_series = 8;     ///< series in one plot
  std::size_t max_nodes = 200;    ///< numbers, fields and operations in one series
  int max_depth = 24;             ///< parentheses, function calls and unary signs nested
};

/// The functions a series may call, by name: degrees(x), radians(x), abs(x), sqrt(x).
inline constexpr std::string_view kFieldFunctions[] = {"degrees", "radians", "abs", "sqrt"};

/// One series: an expression over the fields of one message, evaluated on each frame of it.
class FieldExpression {
 public:
  enum class Op : uint8_t { Number, Field, Negate, Add, Subtract, Multiply, Divide, Degrees, Radians, Abs, Sqrt };
  struct Node {
    Op op = Op::Number;
    double number = 0;                      ///< Number
    const mavlink::FieldDesc* field = nullptr;  ///< Field
    uint8_t index = 0;                      ///< Field: the array element
    int left = -1, right = -1;              ///< operands (node indices); unary ops and calls use left
  };

  std::string text;        ///< the series as written ("ATTITUDE.roll*2")
  uint32_t msgid = 0;
  std::string message;     ///< "ATTITUDE"
  std::vector<Node> nodes; ///< the root is the last
  std::string units;       ///< the field's units when the series is one field alone ("rad"), else ""

  /// The value on a frame of `msgid` (its payload, zero-extended as the parser keeps it); not
  /// finite when the arithmetic makes it so (a division by a field that is 0).
  double evaluate(const uint8_t* payload) const;
};

/// One --plot: its value as given and its series.
struct FieldPlotSpec {
  std::string text;
  std::vector<FieldExpression> series;
};

/// Parses a --plot value against `messages`. An Input error says where and why:
/// "'ATTITUDE.rol' at character 10: ATTITUDE has no field 'rol' (its fields: ...)".
Expected<FieldPlotSpec> parse_field_plot(std::string_view text, const mavlink::MessageSet& messages,
                                         const FieldPlotLimits& limits = {});

}  // namespace hitl::report
