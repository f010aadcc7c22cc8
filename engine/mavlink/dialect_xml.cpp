#include "base/common/bounded_read.h"
#include "engine/mavlink/dialect_xml.h"

#include <pugixml.hpp>

#include <filesystem>
#include <map>
#include <set>

namespace hitl::mavlink {
namespace {

const std::map<std::string, FieldType, std::less<>>& type_names() {
  static const std::map<std::string, FieldType, std::less<>> names = {
      {"char", FieldType::Char},       {"uint8_t", FieldType::Uint8},   {"int8_t", FieldType::Int8},
      {"uint16_t", FieldType::Uint16}, {"int16_t", FieldType::Int16},   {"uint32_t", FieldType::Uint32},
      {"int32_t", FieldType::Int32},   {"uint64_t", FieldType::Uint64}, {"int64_t", FieldType::Int64},
      {"float", FieldType::Float},     {"double", FieldType::Double},   {"uint8_t_mavlink_version", FieldType::Uint8}};
  return names;
}

Expected<FieldDesc> parse_field(const pugi::xml_node& node, bool extension, const std::string& where) {
  FieldDesc f;
  f.name = node.attribute("name").as_string();
  f.units = node.attribute("units").as_string();
  f.enum_name = node.attribute("enum").as_string();
  f.extension = extension;
  std::string type = node.attribute("type").as_string();
  if (f.name.empty()) return Error::input(where + ": a <field> has no name");
  if (auto open = type.find('['); open != std::string::npos) {
    const auto close = type.find(']', open);
    int n = 0;
    try {
      n = std::stoi(type.substr(open + 1, close - open - 1));
    } catch (...) {
      n = 0;
    }
    if (close == std::string::npos || n <= 0 || n > 255)
      return Error::input(where + ": field '" + f.name + "' has a bad array type '" + type + "'");
    f.array_length = static_cast<uint8_t>(n);
    type = type.substr(0, open);
  }
  auto it = type_names().find(type);
  if (it == type_names().end()) return Error::input(where + ": field '" + f.name + "' has unknown type '" + type + "'");
  f.type = it->second;
  return f;
}

Status load_file(const std::filesystem::path& path, MessageSet& set, DialectInfo& info, std::set<std::string>& seen) {
  std::error_code ec;
  const auto canonical = std::filesystem::weakly_canonical(path, ec);
  const std::string key = ec ? path.string() : canonical.string();
  if (!seen.insert(key).second) return Ok{};
  if (!std::filesystem::exists(path)) return Error::input("dialect file '" + path.string() + "' does not exist");
  const auto text = read_bounded_file(path.string(), "dialect file", kMaxDialectFileBytes);
  if (!text) return text.error();
  pugi::xml_document doc;
  const auto result = doc.load_buffer(text->data(), text->size());
  if (!result)
    return Error::input("dialect file '" + path.string() + "' is not valid XML (" + result.description() + " at byte " +
                 std::to_string(result.offset) + ")");
  const auto root = doc.child("mavlink");
  if (!root) return Error::input("dialect file '" + path.string() + "' has no <mavlink> root element");
  for (const auto& inc : root.children("include")) {
    auto included = path.parent_path() / inc.text().as_string();
    if (auto st = load_file(included, set, info, seen); !st) return st;
  }
  for (const auto& m : root.child("messages").children("message")) {
    MessageDesc desc;
    desc.name = m.attribute("name").as_string();
    const std::string where = path.filename().string() + " message " + (desc.name.empty() ? "?" : desc.name);
    const long long id = m.attribute("id").as_llong(-1);
    if (desc.name.empty() || id < 0 || id > 0xFFFFFF) return Error::input(where + ": missing name or id out of range");
    desc.id = static_cast<uint32_t>(id);
    bool extension = false;
    for (const auto& child : m.children()) {
      const std::string tag = child.name();
      if (tag == "extensions") extension = true;
      if (tag != "field") continue;
      auto field = parse_field(child, extension, where);
      if (!field) return field.error();
      desc.fields.push_back(std::move(field.value()));
    }
    assign_wire_order(desc);
    desc.crc_extra = compute_crc_extra(desc);
    set.add(std::move(desc));
    ++info.messages;
  }
  info.files.push_back(path.string());
  return Ok{};
}

}  // namespace

Expected<DialectInfo> load_dialect(const std::string& path, MessageSet& set) {
  DialectInfo info;
  std::set<std::string> seen;
  // Load into a copy so a failure leaves `set` as it was.
  MessageSet staged(set);
  if (auto st = load_file(path, staged, info, seen); !st) return st.error();
  set = std::move(staged);
  return info;
}

}  // namespace hitl::mavlink
