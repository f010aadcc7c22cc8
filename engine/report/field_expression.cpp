#include "engine/report/field_expression.h"

#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <optional>

namespace hitl::report {
namespace {

constexpr std::size_t kMaxNodesEver = 256;  ///< FieldExpression::evaluate's stack; limits.max_nodes is capped here
constexpr double kRadToDeg = 180.0 / M_PI;

bool is_name_start(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_'; }
bool is_name_char(char c) { return is_name_start(c) || (c >= '0' && c <= '9'); }
bool is_digit(char c) { return c >= '0' && c <= '9'; }

/// What went wrong and where (0-based offset into the whole --plot value).
struct Failure {
  std::size_t at = 0;
  std::string why;
};

template <class T>
double load(const uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return static_cast<double>(v);
}

double field_value(const mavlink::FieldDesc& f, uint8_t index, const uint8_t* payload) {
  const uint8_t* p = payload + f.offset + static_cast<std::size_t>(index) * mavlink::size_of(f.type);
  switch (f.type) {
    case mavlink::FieldType::Char: return load<char>(p);
    case mavlink::FieldType::Uint8: return load<uint8_t>(p);
    case mavlink::FieldType::Int8: return load<int8_t>(p);
    case mavlink::FieldType::Uint16: return load<uint16_t>(p);
    case mavlink::FieldType::Int16: return load<int16_t>(p);
    case mavlink::FieldType::Uint32: return load<uint32_t>(p);
    case mavlink::FieldType::Int32: return load<int32_t>(p);
    case mavlink::FieldType::Uint64: return load<uint64_t>(p);
    case mavlink::FieldType::Int64: return load<int64_t>(p);
    case mavlink::FieldType::Float: return load<float>(p);
    case mavlink::FieldType::Double: return load<double>(p);
  }
  return NAN;
}

/// One series' parser over text[begin, end) of the whole value (positions are the whole value's).
class SeriesParser {
 public:
  SeriesParser(std::string_view text, std::size_t begin, std::size_t end, const mavlink::MessageSet& messages,
               const FieldPlotLimits& limits)
      : text_(text), pos_(begin), end_(end), messages_(messages), limits_(limits) {}

  std::optional<Failure> parse(FieldExpression& out) {
    out_ = &out;
    skip_spaces();
    if (pos_ >= end_) return Failure{pos_, "an empty series (two commas, or one at an end)"};
    int root = -1;
    if (auto f = expr(0, root)) return f;
    skip_spaces();
    if (pos_ < end_) return Failure{pos_, "unexpected '" + std::string(1, text_[pos_]) + "' (expected an operator + - * / or the end)"};
    if (out.message.empty()) return Failure{begin_of_series(), "the series names no field (MESSAGE.field)"};
    if (out.nodes.size() == 1 && out.nodes[0].op == FieldExpression::Op::Field) out.units = out.nodes[0].field->units;
    return std::nullopt;
  }

 private:
  std::size_t begin_of_series() const { return first_; }

  void skip_spaces() {
    while (pos_ < end_ && (text_[pos_] == ' ' || text_[pos_] == '\t')) ++pos_;
  }

  std::optional<Failure> add(FieldExpression::Node node, std::size_t at, int& index) {
    if (out_->nodes.size() >= limits_.max_nodes)
      return Failure{at, "the series is too long (more than " + std::to_string(limits_.max_nodes) + " numbers, fields and operations)"};
    out_->nodes.push_back(node);
    index = static_cast<int>(out_->nodes.size()) - 1;
    return std::nullopt;
  }

  std::optional<Failure> deeper(int depth, std::size_t at) const {
    if (depth >= limits_.max_depth)
      return Failure{at, "nested too deep (more than " + std::to_string(limits_.max_depth) + " parentheses, calls and signs)"};
    return std::nullopt;
  }

  std::optional<Failure> expr(int depth, int& out) {
    if (auto f = term(depth, out)) return f;
    for (;;) {
      skip_spaces();
      if (pos_ >= end_ || (text_[pos_] != '+' && text_[pos_] != '-')) return std::nullopt;
      const auto op = text_[pos_] == '+' ? FieldExpression::Op::Add : FieldExpression::Op::Subtract;
      const std::size_t at = pos_++;
      int right = -1;
      if (auto f = term(depth, right)) return f;
      if (auto f = add({op, 0, nullptr, 0, out, right}, at, out)) return f;
    }
  }

  std::optional<Failure> term(int depth, int& out) {
    if (auto f = unary(depth, out)) return f;
    for (;;) {
      skip_spaces();
      if (pos_ >= end_ || (text_[pos_] != '*' && text_[pos_] != '/')) return std::nullopt;
      const auto op = text_[pos_] == '*' ? FieldExpression::Op::Multiply : FieldExpression::Op::Divide;
      const std::size_t at = pos_++;
      skip_spaces();
      const std::size_t divisor_at = pos_;
      int right = -1;
      if (auto f = unary(depth, right)) return f;
      const auto& r = out_->nodes[static_cast<std::size_t>(right)];
      if (op == FieldExpression::Op::Divide && r.op == FieldExpression::Op::Number && r.number == 0)
        return Failure{divisor_at, "a division by zero"};
      if (auto f = add({op, 0, nullptr, 0, out, right}, at, out)) return f;
    }
  }

  std::optional<Failure> unary(int depth, int& out) {
    skip_spaces();
    if (pos_ < end_ && (text_[pos_] == '-' || text_[pos_] == '+')) {
      const bool negate = text_[pos_] == '-';
      const std::size_t at = pos_++;
      if (auto f = deeper(depth, at)) return f;
      if (auto f = unary(depth + 1, out)) return f;
      if (negate) return add({FieldExpression::Op::Negate, 0, nullptr, 0, out, -1}, at, out);
      return std::nullopt;
    }
    return primary(depth, out);
  }

  std::optional<Failure> primary(int depth, int& out) {
    skip_spaces();
    if (pos_ >= end_) return Failure{pos_, "the series ends where a number, a field or '(' was expected"};
    const char c = text_[pos_];
    if (c == '(') {
      const std::size_t open = pos_++;
      if (auto f = deeper(depth, open)) return f;
      if (auto f = expr(depth + 1, out)) return f;
      return close_paren(open);
    }
    if (is_digit(c) || c == '.') return number(out);
    if (!is_name_start(c)) return Failure{pos_, "unexpected '" + std::string(1, c) + "' (expected a number, MESSAGE.field, a function or '(')"};
    const std::size_t name_at = pos_;
    while (pos_ < end_ && is_name_char(text_[pos_])) ++pos_;
    const std::string name(text_.substr(name_at, pos_ - name_at));
    skip_spaces();
    if (pos_ < end_ && text_[pos_] == '(') return call(name, name_at, depth, out);
    if (pos_ < end_ && text_[pos_] == '.') return field(name, name_at, out);
    return Failure{name_at, "'" + name + "' is neither MESSAGE.field nor a function (" + function_list() + ")"};
  }

  std::optional<Failure> close_paren(std::size_t open) {
    skip_spaces();
    if (pos_ >= end_ || text_[pos_] != ')') return Failure{open, "'(' without its ')'"};
    ++pos_;
    return std::nullopt;
  }

  static std::string function_list() {
    std::string s;
    for (auto f : kFieldFunctions) s += (s.empty() ? "" : ", ") + std::string(f);
    return s;
  }

  std::optional<Failure> number(int& out) {
    const std::size_t at = pos_;
    while (pos_ < end_ && (is_digit(text_[pos_]) || text_[pos_] == '.')) ++pos_;
    if (pos_ < end_ && (text_[pos_] == 'e' || text_[pos_] == 'E')) {
      std::size_t k = pos_ + 1;
      if (k < end_ && (text_[k] == '+' || text_[k] == '-')) ++k;
      if (k < end_ && is_digit(text_[k])) {
        pos_ = k;
        while (pos_ < end_ && is_digit(text_[pos_])) ++pos_;
      }
    }
    double v = 0;
    const char* first = text_.data() + at;
    const char* last = text_.data() + pos_;
    const auto [ptr, ec] = std::from_chars(first, last, v);
    if (ec == std::errc::result_out_of_range || (ec == std::errc() && !std::isfinite(v)))
      return Failure{at, "'" + std::string(first, last) + "' is not a finite number"};
    if (ec != std::errc() || ptr != last) return Failure{at, "'" + std::string(first, last) + "' is not a number"};
    if (pos_ < end_ && is_name_start(text_[pos_])) return Failure{pos_, "a name right after the number '" + std::string(first, last) + "'"};
    return add({FieldExpression::Op::Number, v, nullptr, 0, -1, -1}, at, out);
  }

  std::optional<Failure> call(const std::string& name, std::size_t name_at, int depth, int& out) {
    static constexpr std::array<FieldExpression::Op, 4> ops = {FieldExpression::Op::Degrees, FieldExpression::Op::Radians,
                                                               FieldExpression::Op::Abs, FieldExpression::Op::Sqrt};
    std::optional<FieldExpression::Op> op;
    for (std::size_t k = 0; k < ops.size(); ++k)
      if (name == kFieldFunctions[k]) op = ops[k];
    if (!op) return Failure{name_at, "no function '" + name + "' (there are " + function_list() + ")"};
    const std::size_t open = pos_++;
    if (auto f = deeper(depth, open)) return f;
    int arg = -1;
    if (auto f = expr(depth + 1, arg)) return f;
    if (auto f = close_paren(open)) return f;
    return add({*op, 0, nullptr, 0, arg, -1}, name_at, out);
  }

  std::optional<Failure> field(const std::string& message_name, std::size_t name_at, int& out) {
    const mavlink::MessageDesc* message = messages_.find(message_name);
    if (message == nullptr) {
      std::string known;
      for (const auto* m : messages_.all()) known += (known.empty() ? "" : ", ") + m->name;
      return Failure{name_at, "no message '" + message_name + "' in hitl's MAVLink set (" + known + ")"};
    }
    if (!out_->message.empty() && out_->message != message->name)
      return Failure{name_at, "a series takes the fields of one message: this one is of " + out_->message + ", not " + message->name};
    ++pos_;  // '.'
    const std::size_t field_at = pos_;
    while (pos_ < end_ && is_name_char(text_[pos_])) ++pos_;
    const std::string field_name(text_.substr(field_at, pos_ - field_at));
    const mavlink::FieldDesc* field = message->field(field_name);
    if (field == nullptr) {
      std::string known;
      for (const auto& f : message->fields) known += (known.empty() ? "" : ", ") + f.name;
      return Failure{field_at, field_name.empty() ? message->name + ". without a field (its fields: " + known + ")"
                                                  : message->name + " has no field '" + field_name + "' (its fields: " + known + ")"};
    }
    if (field->type == mavlink::FieldType::Char && field->array_length > 0)
      return Failure{field_at, message->name + "." + field_name + " is text, not a number"};
    uint8_t index = 0;
    skip_spaces();
    const bool indexed = pos_ < end_ && text_[pos_] == '[';
    if (field->array_length > 0 && !indexed)
      return Failure{field_at, message->name + "." + field_name + " is an array of " + std::to_string(field->array_length) +
                                   ": name one element, " + field_name + "[0] to " + field_name + "[" +
                                   std::to_string(field->array_length - 1) + "]"};
    if (indexed) {
      const std::size_t open = pos_++;
      if (field->array_length == 0) return Failure{open, message->name + "." + field_name + " is not an array"};
      skip_spaces();
      const std::size_t index_at = pos_;
      while (pos_ < end_ && is_digit(text_[pos_])) ++pos_;
      unsigned long i = 0;
      const auto [ptr, ec] = std::from_chars(text_.data() + index_at, text_.data() + pos_, i);
      if (pos_ == index_at || ec != std::errc() || i >= field->array_length)
        return Failure{index_at, "the index of " + message->name + "." + field_name + " is 0 to " +
                                     std::to_string(field->array_length - 1)};
      index = static_cast<uint8_t>(i);
      skip_spaces();
      if (pos_ >= end_ || text_[pos_] != ']') return Failure{open, "'[' without its ']'"};
      ++pos_;
    }
    if (out_->message.empty()) out_->message = message->name, out_->msgid = message->id;
    return add({FieldExpression::Op::Field, 0, field, index, -1, -1}, name_at, out);
  }

  std::string_view text_;
  std::size_t pos_, end_;
  std::size_t first_ = pos_;
  const mavlink::MessageSet& messages_;
  const FieldPlotLimits& limits_;
  FieldExpression* out_ = nullptr;
};

std::string trimmed(std::string_view s) {
  std::size_t b = 0, e = s.size();
  while (b < e && (s[b] == ' ' || s[b] == '\t')) ++b;
  while (e > b && (s[e - 1] == ' ' || s[e - 1] == '\t')) --e;
  return std::string(s.substr(b, e - b));
}

}  // namespace

double FieldExpression::evaluate(const uint8_t* payload) const {
  std::array<double, kMaxNodesEver> v{};
  const std::size_t n = std::min(nodes.size(), v.size());
  for (std::size_t i = 0; i < n; ++i) {
    const Node& node = nodes[i];
    const double a = node.left >= 0 ? v[static_cast<std::size_t>(node.left)] : 0;
    const double b = node.right >= 0 ? v[static_cast<std::size_t>(node.right)] : 0;
    switch (node.op) {
      case Op::Number: v[i] = node.number; break;
      case Op::Field: v[i] = field_value(*node.field, node.index, payload); break;
      case Op::Negate: v[i] = -a; break;
      case Op::Add: v[i] = a + b; break;
      case Op::Subtract: v[i] = a - b; break;
      case Op::Multiply: v[i] = a * b; break;
      case Op::Divide: v[i] = a / b; break;
      case Op::Degrees: v[i] = a * kRadToDeg; break;
      case Op::Radians: v[i] = a / kRadToDeg; break;
      case Op::Abs: v[i] = std::abs(a); break;
      case Op::Sqrt: v[i] = std::sqrt(a); break;
    }
  }
  return n == 0 ? NAN : v[n - 1];
}

Expected<FieldPlotSpec> parse_field_plot(std::string_view text, const mavlink::MessageSet& messages, const FieldPlotLimits& limits) {
  const std::string quoted = "'" + std::string(text.substr(0, std::min<std::size_t>(text.size(), 80))) + (text.size() > 80 ? "...'" : "'");
  auto fail = [&](const Failure& f) {
    return Error::input(quoted + " at character " + std::to_string(f.at + 1) + ": " + f.why);
  };
  if (text.size() > limits.max_chars)
    return fail({limits.max_chars, "longer than " + std::to_string(limits.max_chars) + " characters"});
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c >= 0x7f) return fail({i, "a character that is not printable ASCII (byte " + std::to_string(c) + ")"});
  }
  FieldPlotLimits capped = limits;
  capped.max_nodes = std::min(limits.max_nodes, kMaxNodesEver);
  FieldPlotSpec spec;
  spec.text = std::string(text);
  // Series end at commas outside parentheses and brackets.
  std::size_t begin = 0;
  int nesting = 0;
  for (std::size_t i = 0; i <= text.size(); ++i) {
    const char c = i < text.size() ? text[i] : ',';
    if (c == '(' || c == '[') ++nesting;
    if ((c == ')' || c == ']') && nesting > 0) --nesting;
    if (c != ',' || (nesting > 0 && i < text.size())) continue;
    if (spec.series.size() >= capped.max_series)
      return fail({begin, "more than " + std::to_string(capped.max_series) + " series in one plot"});
    FieldExpression e;
    SeriesParser parser(text, begin, i, messages, capped);
    if (auto f = parser.parse(e)) return fail(*f);
    e.text = trimmed(text.substr(begin, i - begin));
    spec.series.push_back(std::move(e));
    begin = i + 1;
  }
  return spec;
}

}  // namespace hitl::report
