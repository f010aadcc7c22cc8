// A ULog 'F' format ("name:type field;type[n] field;") parsed, and where a top-level field lies in
// a topic's bytes: the offset adds up the sizes of the fields before it, nested formats included
// (resolved through the other formats, at most Limits::max_nesting deep; a cycle is unusable).
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace hitl::ulog {

enum class BasicType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Int64, UInt64, Float, Double, Bool, Char };

struct FormatField {
  std::string type;        ///< "float", "uint64_t", or another format's name
  std::size_t count = 1;   ///< array length; 1 for a single value
  bool array = false;
  std::string name;
};

struct Format {
  std::string name;
  std::vector<FormatField> fields;
};

/// "float" -> Float; nullopt for a nested format's name.
std::optional<BasicType> basic_type(std::string_view name);
std::size_t basic_size(BasicType type);

/// The format text of an 'F' message, or nullopt when it is not one ("name:" then at least one
/// "type name;" with a sane type, array length and name).
std::optional<Format> parse_format(std::string_view text);

/// A basic field's place in a topic's bytes.
struct FieldLocation {
  BasicType type = BasicType::UInt8;
  std::size_t offset = 0;
};

/// Sizes of formats by name, resolved once each (a nested type, a cycle, a missing type).
class Layouts {
 public:
  Layouts(const std::map<std::string, Format>& formats, int max_nesting) : formats_(formats), max_nesting_(max_nesting) {}
  /// The size in bytes of the format `name` (its trailing padding included), or nullopt when it
  /// cannot be laid out (a missing type, a cycle, too deep, larger than 1 MiB).
  std::optional<std::size_t> size_of(const std::string& name) { return size_at(name, 0); }
  /// Where `field` ("x", "q[2]") of the format `topic` lies: a top-level field of a basic type, an
  /// array's element by index. nullopt when there is no such basic field.
  std::optional<FieldLocation> locate(const std::string& topic, std::string_view field);

 private:
  std::optional<std::size_t> size_at(const std::string& name, int depth);
  std::optional<std::size_t> field_size(const FormatField& f, int depth);
  const std::map<std::string, Format>& formats_;
  int max_nesting_;
  std::map<std::string, std::optional<std::size_t>> sizes_;
};

/// The value of a basic field at `p` (little endian), as a double.
double decode_basic(BasicType type, const uint8_t* p);

}  // namespace hitl::ulog
