#include "engine/vehicle/params_push.h"

#include <map>

#include "engine/vehicle/firmware_version.h"

namespace hitl::vehicle {

ParamPushResult push_params(ParamClient& client, VehicleLink& link, const std::vector<Param>& board,
                            const std::vector<Param>& wanted, const ParamPushOptions& options) {
  std::map<std::string, ParamValue> current;
  for (const auto& p : board) current[p.name] = p.value;
  ParamPushResult result;
  for (const auto& p : wanted) {
    const auto it = current.find(p.name);
    if (it == current.end()) {
      if (!options.absent_ok) {
        result.failed.push_back({p.name, "the board has no such parameter"});
        continue;
      }
      if (result.absent.empty()) result.firmware = request_firmware_version(link);
      result.absent.push_back({p.name, find_absent_note(p.name)});
      continue;
    }
    if (it->second == p.value) {
      result.unchanged.push_back(p.name);
      continue;
    }
    if (options.dry_run) {
      result.set.push_back({p.name, it->second, p.value});
      continue;
    }
    const auto r = client.set(p.name, p.value);
    const auto back = r ? client.get(p.name) : Expected<ParamValue>(r.error());
    if (r && back && *back == p.value) result.set.push_back({p.name, it->second, p.value});
    else
      result.failed.push_back({p.name, !r ? r.error().message : (!back ? back.error().message : "read back " + back->to_string())});
  }
  return result;
}

}  // namespace hitl::vehicle
