// The config files' JSON machinery, apart from the keys: a field table (config_json.cpp's
// vehicle_fields / world_fields) is one function over a visitor, and the visitors here read it
// (Reader: merge over a base, range checks, every error with its key path, unknown keys) or write
// it (Writer). parse() and write() run a table over a whole document.
// Private to the config readers (nlohmann_json is a private dependency): config_json.cpp and the
// sensor units' keys (engine/sensors/vehicle_file.cpp) include it.
#pragma once

#include <array>
#include <cmath>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "base/common/expected.h"
#include "base/common/json_nesting.h"
#include "engine/model/config_range.h"
#include "engine/model/vehicle_config.h"

namespace hitl::model::config_fields {

using json = nlohmann::json;

inline std::string child_path(const std::string& parent, std::string_view key) {
  return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}

/// Reads the keys a fields() function names from one JSON object into a config that already holds
/// the base values. Errors collect in a shared list as "path: what".
class Reader {
 public:
  Reader(const json& object, std::string path, std::vector<std::string>& errors)
      : object_(object), path_(std::move(path)), errors_(errors) {}

  void number(const char* key, double& out, Range range) {
    const json* j = find(key);
    if (j && check_number(*j, key, range)) out = j->get<double>();
  }
  void integer(const char* key, int& out, Range range) {
    const json* j = find(key);
    if (!j) return;
    if (!j->is_number_integer()) return fail(key, "must be an integer (got " + j->dump() + ")");
    if (!range.contains(j->get<double>())) return fail(key, range.describe() + " (got " + j->dump() + ")");
    out = j->get<int>();
  }
  void boolean(const char* key, bool& out) {
    const json* j = find(key);
    if (!j) return;
    if (!j->is_boolean()) return fail(key, "must be true or false (got " + j->dump() + ")");
    out = j->get<bool>();
  }
  void text(const char* key, std::string& out) {
    const json* j = find(key);
    if (!j) return;
    if (!j->is_string()) return fail(key, "must be a string (got " + j->dump() + ")");
    out = j->get<std::string>();
  }
  void turning(const char* key, Turning& out) {
    const json* j = find(key);
    if (!j) return;
    if (*j == "ccw") out = Turning::Ccw;
    else if (*j == "cw") out = Turning::Cw;
    else fail(key, "must be \"ccw\" or \"cw\" (got " + j->dump() + ")");
  }
  void vec3(const char* key, Eigen::Vector3d& out, Range range) {
    const json* j = find(key);
    if (j) read_vec3(*j, child_path(path_, key), out, range);
  }
  template <std::size_t N>
  void vec3_array(const char* key, std::array<Eigen::Vector3d, N>& out, Range range) {
    const json* j = find(key);
    if (!j || !check_array(*j, key, N)) return;
    for (std::size_t i = 0; i < N; ++i) read_vec3((*j)[i], index_path(key, i), out[i], range);
  }
  template <class Fields>
  void object(const char* key, Fields&& fields) {
    const json* j = find(key);
    if (!j) return;
    if (!j->is_object()) return fail(key, "must be an object (got " + j->dump() + ")");
    Reader sub(*j, child_path(path_, key), errors_);
    fields(sub);
    sub.finish();
  }
  template <class T, std::size_t N, class Fields>
  void object_array(const char* key, std::array<T, N>& out, Fields&& fields) {
    const json* j = find(key);
    if (!j || !check_array(*j, key, N)) return;
    for (std::size_t i = 0; i < N; ++i) {
      const json& item = (*j)[i];
      if (!item.is_object()) {
        errors_.push_back(index_path(key, i) + ": must be an object (got " + item.dump() + ")");
        continue;
      }
      Reader sub(item, index_path(key, i), errors_);
      fields(sub, out[i]);
      sub.finish();
    }
  }
  /// Reports every key of the object that no field asked for.
  void finish() {
    for (const auto& item : object_.items()) {
      bool known = false;
      for (const std::string& k : seen_) known = known || k == item.key();
      if (!known) errors_.push_back(child_path(path_, item.key()) + ": unknown key");
    }
  }

 private:
  const json* find(const char* key) {
    seen_.emplace_back(key);
    auto it = object_.find(key);
    return it == object_.end() ? nullptr : &*it;
  }
  void fail(const char* key, const std::string& what) { errors_.push_back(child_path(path_, key) + ": " + what); }
  std::string index_path(const char* key, std::size_t i) const {
    return child_path(path_, key) + "[" + std::to_string(i) + "]";
  }
  bool check_number(const json& j, const char* key, Range range) {
    if (!j.is_number()) {
      fail(key, "must be a number (got " + j.dump() + ")");
      return false;
    }
    if (!range.contains(j.get<double>())) {
      fail(key, range.describe() + " (got " + j.dump() + ")");
      return false;
    }
    return true;
  }
  bool check_array(const json& j, const char* key, std::size_t n) {
    if (j.is_array() && j.size() == n) return true;
    fail(key, "must be an array of " + std::to_string(n) + " (got " + j.dump() + ")");
    return false;
  }
  void read_vec3(const json& j, const std::string& path, Eigen::Vector3d& out, Range range) {
    if (!j.is_array() || j.size() != 3) {
      errors_.push_back(path + ": must be an array of 3 numbers (got " + j.dump() + ")");
      return;
    }
    Eigen::Vector3d v;
    for (int i = 0; i < 3; ++i) {
      const json& e = j[static_cast<std::size_t>(i)];
      if (!e.is_number() || !range.contains(e.get<double>())) {
        errors_.push_back(path + "[" + std::to_string(i) + "]: " +
                          (e.is_number() ? range.describe() : std::string("must be a number")) + " (got " + e.dump() + ")");
        return;
      }
      v[i] = e.get<double>();
    }
    out = v;
  }

  const json& object_;
  std::string path_;
  std::vector<std::string>& errors_;
  std::vector<std::string> seen_;
};

/// Writes the same fields to a JSON object (ranges are ignored).
class Writer {
 public:
  explicit Writer(json& object) : object_(object) { object_ = json::object(); }

  void number(const char* key, const double& v, Range) { object_[key] = v; }
  void integer(const char* key, const int& v, Range) { object_[key] = v; }
  void boolean(const char* key, const bool& v) { object_[key] = v; }
  void text(const char* key, const std::string& v) { object_[key] = v; }
  void turning(const char* key, const Turning& v) { object_[key] = v == Turning::Ccw ? "ccw" : "cw"; }
  void vec3(const char* key, const Eigen::Vector3d& v, Range) { object_[key] = to_json(v); }
  template <std::size_t N>
  void vec3_array(const char* key, const std::array<Eigen::Vector3d, N>& v, Range) {
    json a = json::array();
    for (const Eigen::Vector3d& e : v) a.push_back(to_json(e));
    object_[key] = a;
  }
  template <class Fields>
  void object(const char* key, Fields&& fields) {
    Writer sub(object_[key]);
    fields(sub);
  }
  template <class T, std::size_t N, class Fields>
  void object_array(const char* key, const std::array<T, N>& items, Fields&& fields) {
    json a = json::array();
    for (const T& item : items) {
      json o;
      Writer sub(o);
      fields(sub, const_cast<T&>(item));  // fields() takes T&; the Writer only reads it
      a.push_back(o);
    }
    object_[key] = a;
  }

 private:
  static json to_json(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }
  json& object_;
};

template <class Config, class Fields>
Expected<Config> parse(std::string_view text, std::string_view source_name, Config config, Fields fields) {
  const std::string source(source_name);
  if (auto depth = check_json_depth(text, source); !depth) return depth.error();
  json root;
  try {
    root = json::parse(text.begin(), text.end(), nullptr, /*allow_exceptions=*/true, /*ignore_comments=*/true);
  } catch (const json::exception& e) {  // parse_error, and out_of_range for a number like 1e400
    return Error::input(source + ": not valid JSON: " + e.what());
  }
  if (!root.is_object()) return Error::input(source + ": must be a JSON object (got " + std::string(root.type_name()) + ")");
  std::vector<std::string> errors;
  Reader reader(root, "", errors);
  fields(reader, config);
  reader.finish();
  if (errors.empty()) return config;
  std::string message;
  for (const std::string& e : errors) message += (message.empty() ? "" : "\n") + source + ": " + e;
  return Error::input(message);
}

template <class Config, class Fields>
std::string write(const Config& config, Fields fields) {
  json root;
  Writer writer(root);
  fields(writer, const_cast<Config&>(config));  // fields() takes Config&; the Writer only reads it
  return root.dump(2);
}

}  // namespace hitl::model::config_fields
