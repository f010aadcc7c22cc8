#include "engine/vehicle/param_client.h"

#include <cstring>
#include <map>
#include <optional>

#include "base/mavlink/enums.h"
#include "base/mavlink/text_field.h"
#include "engine/vehicle/board_replies.h"

namespace hitl::vehicle {
namespace {

namespace msg = mavlink::msg;

}  // namespace

Expected<std::vector<Param>> ParamClient::download(const std::function<void(std::size_t, std::size_t)>& progress) {
  ParamCollector got;
  auto take = [&](const mavlink::Frame& f) {
    if (!f.is<msg::ParamValue>()) return false;
    const std::size_t before = got.received();
    const bool done = got.take(f.as<msg::ParamValue>());
    if (progress && got.received() > before) progress(got.received(), *got.total());
    return done;
  };
  msg::ParamRequestList list;
  list.target_system = link_.target_sysid();
  list.target_component = link_.target_compid();
  for (int attempt = 0; attempt < kRetries && !got.total(); ++attempt) {
    link_.send(list);
    link_.wait(kTimeout_s * 2, take);  // until every index arrived, or the burst went quiet
  }
  if (!got.total()) return Error::failed("no PARAM_VALUE in answer to PARAM_REQUEST_LIST");
  for (int round = 0; round < kRetries && got.received() < *got.total(); ++round) {
    for (uint16_t i = 0; i < *got.total(); ++i) {
      if (got.has(i)) continue;
      msg::ParamRequestRead read;
      read.target_system = link_.target_sysid();
      read.target_component = link_.target_compid();
      read.param_index = static_cast<int16_t>(i);
      link_.send(read);
    }
    link_.wait(kTimeout_s, take);
  }
  if (got.received() < *got.total())
    return Error::failed("received " + std::to_string(got.received()) + " of " + std::to_string(*got.total()) + " parameters after " +
                         std::to_string(kRetries) + " rounds of re-requests");
  return got.params();
}

Expected<ParamValue> ParamClient::get(const std::string& name) {
  msg::ParamRequestRead read;
  read.target_system = link_.target_sysid();
  read.target_component = link_.target_compid();
  read.param_index = -1;
  mavlink::set_text(read.param_id, name);
  std::optional<ParamValue> value;
  for (int attempt = 0; attempt < kRetries && !value; ++attempt) {
    link_.send(read);
    link_.wait(kTimeout_s, [&](const mavlink::Frame& f) {
      if (!f.is<msg::ParamValue>()) return false;
      const auto v = f.as<msg::ParamValue>();
      if (param_name(v.param_id) != name) return false;
      value = param_value_of(v);
      return true;
    });
  }
  if (!value) return Error::failed("no answer for parameter " + name + " (it may not exist on this board)");
  return *value;
}

Expected<ParamValue> ParamClient::set(const std::string& name, const ParamValue& value) {
  msg::ParamSet set;
  set.target_system = link_.target_sysid();
  set.target_component = link_.target_compid();
  mavlink::set_text(set.param_id, name);
  set.param_value = encode_param_float(value);
  set.param_type = static_cast<uint8_t>(value.type);
  std::optional<ParamValue> echo;
  for (int attempt = 0; attempt < kRetries && !echo; ++attempt) {
    link_.send(set);
    link_.wait(kTimeout_s, [&](const mavlink::Frame& f) {
      if (!f.is<msg::ParamValue>()) return false;
      const auto v = f.as<msg::ParamValue>();
      if (param_name(v.param_id) != name) return false;
      echo = param_value_of(v);
      return true;
    });
  }
  if (!echo) return Error::failed(name + ": no PARAM_VALUE echo after " + std::to_string(kRetries) + " tries");
  if (!(*echo == value)) return Error::failed(name + ": the board kept " + echo->to_string() + " (asked for " + value.to_string() + ")");
  return *echo;
}

}  // namespace hitl::vehicle
