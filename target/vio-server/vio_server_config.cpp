#include "base/common/bounded_read.h"
#include "base/common/json_nesting.h"
#include "target/vio-server/vio_server_config.h"

#include <arpa/inet.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <system_error>

namespace hitl::vio {

extern const char* const kDefaultConfigText;  // generated from voxl-hitl-vio-server.conf

namespace {

constexpr const char* kKeyReceiverIp = "receiver_ip";
constexpr const char* kKeyReceiverPort = "receiver_port";

std::string prefix(std::string_view source, std::string_view key) {
  return std::string(source) + ": \"" + std::string(key) + "\" ";
}

Expected<VioServerConfig> apply(const nlohmann::json& doc, VioServerConfig config, std::string_view source) {
  if (!doc.is_object()) return Error{std::string(source) + ": expected a JSON object with \"receiver_ip\" and \"receiver_port\""};
  for (const auto& [key, value] : doc.items()) {
    if (key == kKeyReceiverIp) {
      if (!value.is_string()) return Error{prefix(source, key) + "must be a string such as \"0.0.0.0\", not " + value.dump()};
      const std::string ip = value.get<std::string>();
      in_addr addr{};
      if (::inet_pton(AF_INET, ip.c_str(), &addr) != 1) {
        return Error{prefix(source, key) + "must be an IPv4 address such as \"0.0.0.0\", not \"" + ip + "\""};
      }
      config.receiver_ip = ip;
    } else if (key == kKeyReceiverPort) {
      if (!value.is_number_integer() || value.get<int64_t>() < 1 || value.get<int64_t>() > 65535) {
        return Error{prefix(source, key) + "must be an integer port 1..65535, not " + value.dump()};
      }
      config.receiver_port = static_cast<uint16_t>(value.get<int64_t>());
    } else {
      return Error{prefix(source, key) + "is not a key of this file (known: \"receiver_ip\", \"receiver_port\")"};
    }
  }
  return config;
}

Expected<VioServerConfig> parse_with(std::string_view text, std::string_view source, VioServerConfig base) {
  if (auto depth = check_json_depth(text, std::string(source)); !depth) return depth.error();
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {  // parse_error, and out_of_range for a number like 1e400
    return Error{std::string(source) + ": not valid JSON (" + e.what() + ")"};
  }
  return apply(doc, std::move(base), source);
}

}  // namespace

std::string_view default_config_text() { return kDefaultConfigText; }

VioServerConfig default_config() {
  auto parsed = parse_with(default_config_text(), "the built-in default voxl-hitl-vio-server.conf", VioServerConfig{});
  // The packaged file is checked by the unit tests; a broken one is a build defect, not input.
  if (!parsed.ok()) throw std::logic_error(parsed.error().message);
  return parsed.value();
}

Expected<VioServerConfig> parse_config(std::string_view text, std::string_view source) {
  return parse_with(text, source, default_config());
}

Expected<LoadedConfig> load_or_create_config(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    const auto dir = std::filesystem::path(path).parent_path();
    if (!dir.empty()) std::filesystem::create_directories(dir, ec);
    if (ec) return Error{"cannot create " + dir.string() + " for " + path + ": " + ec.message()};
    std::ofstream out(path);
    out << default_config_text();
    out.close();
    if (!out) return Error{"cannot write the default configuration to " + path + ": " + std::strerror(errno)};
    return LoadedConfig{default_config(), true};
  }
  if (std::filesystem::is_directory(path, ec)) return Error{path + " is a directory, not a configuration file"};
  auto text = read_bounded_file(path, "configuration file", kMaxConfigFileBytes);
  if (!text) return text.error();
  auto config = parse_config(*text, path);
  if (!config.ok()) return config.error();
  return LoadedConfig{config.value(), false};
}

}  // namespace hitl::vio
