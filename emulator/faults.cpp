#include "emulator/faults.h"

#include <array>

#include "base/contract/device_ids.h"

namespace hitl::target {
namespace {

constexpr std::array<Fault, 7> kAll = {Fault::NoActuators,    Fault::WrongFlags,         Fault::WrongCalAcc0Id,
                                       Fault::SysHitl0,       Fault::DspHitlStalled,     Fault::EkfNotConverging,
                                       Fault::NoVioListener};

// The wrong accel ID is the right one on another address: same device type, still not dsp_hitl's.
static_assert(kWrongAccelDeviceId == static_cast<int32_t>(make_device_id(DeviceBusType::Simulation, 1, 0x02, kDevtypeImuSim)));
static_assert(kWrongAccelDeviceId != static_cast<int32_t>(kDeviceIdImu));

}  // namespace

const char* to_string(Fault fault) {
  switch (fault) {
    case Fault::NoActuators: return "no-actuators";
    case Fault::WrongFlags: return "wrong-flags";
    case Fault::WrongCalAcc0Id: return "wrong-cal-acc0-id";
    case Fault::SysHitl0: return "sys-hitl-0";
    case Fault::DspHitlStalled: return "dsp-hitl-stalled";
    case Fault::EkfNotConverging: return "ekf-not-converging";
    case Fault::NoVioListener: return "no-vio-listener";
  }
  return "?";
}

const std::vector<std::string>& fault_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (Fault f : kAll) v.emplace_back(to_string(f));
    return v;
  }();
  return names;
}

Expected<Fault> parse_fault(const std::string& name) {
  for (Fault f : kAll)
    if (name == to_string(f)) return f;
  std::string valid;
  for (const auto& n : fault_names()) valid += (valid.empty() ? "" : ", ") + n;
  return Error::input("'" + name + "' is not a fault this board can inject (" + valid + ")");
}

void BoardFaults::set(Fault fault) {
  switch (fault) {
    case Fault::NoActuators: no_actuators = true; break;
    case Fault::WrongFlags: wrong_flags = true; break;
    case Fault::WrongCalAcc0Id: wrong_cal_acc0_id = true; break;
    case Fault::SysHitl0: sys_hitl_0 = true; break;
    case Fault::DspHitlStalled: dsp_hitl_stalled = true; break;
    case Fault::EkfNotConverging: ekf_not_converging = true; break;
    case Fault::NoVioListener: no_vio_listener = true; break;
  }
}

bool BoardFaults::any() const { return !names().empty(); }

std::string BoardFaults::names() const {
  const std::array<bool, 7> on = {no_actuators, wrong_flags, wrong_cal_acc0_id, sys_hitl_0,
                                  dsp_hitl_stalled, ekf_not_converging, no_vio_listener};
  std::string out;
  for (std::size_t i = 0; i < kAll.size(); ++i)
    if (on[i]) out += (out.empty() ? "" : ", ") + std::string(to_string(kAll[i]));
  return out;
}

}  // namespace hitl::target
