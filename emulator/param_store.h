// The emulated board's parameters: PX4-typed (INT32 / REAL32), in a fixed order (PARAM_VALUE's
// param_index), with ranges; a set of the wrong type or out of range is refused.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "engine/vehicle/params_file.h"

namespace hitl::target {

class ParamStore {
 public:
  /// Adds a parameter (or replaces its default when it exists). `min`/`max` bound later sets.
  void add(const std::string& name, vehicle::ParamValue value, std::optional<double> min = std::nullopt,
           std::optional<double> max = std::nullopt);
  const vehicle::ParamValue* get(const std::string& name) const;
  /// Sets a parameter; an Error naming the parameter when unknown, of another type, or out of range.
  Expected<vehicle::ParamValue> set(const std::string& name, vehicle::ParamValue value);
  std::size_t size() const { return params_.size(); }
  const vehicle::Param& at(std::size_t index) const { return params_[index].param; }
  std::optional<std::size_t> index_of(const std::string& name) const;
  /// Called after each successful set.
  void on_change(std::function<void(const vehicle::Param&)> callback) { on_change_ = std::move(callback); }

 private:
  struct Entry {
    vehicle::Param param;
    std::optional<double> min, max;
  };
  std::vector<Entry> params_;
  std::map<std::string, std::size_t> index_;
  std::function<void(const vehicle::Param&)> on_change_;
};

}  // namespace hitl::target
