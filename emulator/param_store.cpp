#include "emulator/param_store.h"

#include <cmath>

namespace hitl::target {

void ParamStore::add(const std::string& name, vehicle::ParamValue value, std::optional<double> min, std::optional<double> max) {
  if (auto it = index_.find(name); it != index_.end()) {
    params_[it->second] = Entry{{name, value}, min, max};
    return;
  }
  index_[name] = params_.size();
  params_.push_back(Entry{{name, value}, min, max});
}

const vehicle::ParamValue* ParamStore::get(const std::string& name) const {
  auto it = index_.find(name);
  return it == index_.end() ? nullptr : &params_[it->second].param.value;
}

std::optional<std::size_t> ParamStore::index_of(const std::string& name) const {
  auto it = index_.find(name);
  if (it == index_.end()) return std::nullopt;
  return it->second;
}

Expected<vehicle::ParamValue> ParamStore::set(const std::string& name, vehicle::ParamValue value) {
  auto it = index_.find(name);
  if (it == index_.end()) return Error{"unknown parameter " + name};
  Entry& e = params_[it->second];
  if (value.type != e.param.value.type)
    return Error{name + " is " + (e.param.value.type == vehicle::ParamType::Int32 ? "INT32" : "REAL32") + ", not " +
                 (value.type == vehicle::ParamType::Int32 ? "INT32" : "REAL32")};
  const double v = value.as_double();
  if (!std::isfinite(v)) return Error{name + ": value is not finite"};
  if ((e.min && v < *e.min) || (e.max && v > *e.max))
    return Error{name + ": " + value.to_string() + " is outside " + std::to_string(e.min.value_or(-INFINITY)) + ".." +
                 std::to_string(e.max.value_or(INFINITY))};
  e.param.value = value;
  if (on_change_) on_change_(e.param);
  return value;
}

}  // namespace hitl::target
