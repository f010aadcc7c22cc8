#include "engine/doctor/vio_checks.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <sstream>

#include "engine/doctor/check_catalog.h"

namespace hitl::doctor {
namespace {

std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \r\n\t");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \r\n\t");
  return s.substr(b, e - b + 1);
}

const char* kStartServer = "adb shell systemctl enable --now voxl-hitl-vio-server";

}  // namespace

CheckResult vio_skipped(const char* id, const std::string& why) { return make_result(id, Verdict::Skip, why); }

CheckResult vio_odometry_check(const BoardOutput& status_json, double expected_hz) {
  if (!status_json) return vio_skipped(check::kVioOdometry, status_json.error().message);
  // The report is the last line that parses as a JSON object (a shell may echo the command first).
  nlohmann::json doc;
  std::istringstream in(status_json.value());
  std::string line;
  while (std::getline(in, line)) {
    const auto j = nlohmann::json::parse(trimmed(line), nullptr, false);
    if (!j.is_discarded() && j.is_object()) doc = j;
  }
  if (!doc.is_object() || !doc.contains("running") || !doc["running"].is_boolean())
    return make_result(check::kVioOdometry, Verdict::Fail,
                       "voxl-hitl-vio-server --status --json gave no report: '" + trimmed(status_json.value()).substr(0, 120) + "'",
                       "install voxl-hitl-vio-server on the board (its .deb), then: " + std::string(kStartServer));
  if (!doc["running"].get<bool>()) {
    const std::string why = doc.contains("error") && doc["error"].is_string() ? doc["error"].get<std::string>() : "not running";
    return make_result(check::kVioOdometry, Verdict::Fail, "nothing listens for ODOMETRY: " + why, kStartServer);
  }
  const double hz = doc.contains("odometry_rate_hz") && doc["odometry_rate_hz"].is_number() ? doc["odometry_rate_hz"].get<double>() : 0.0;
  const std::string listen = doc.contains("listen") && doc["listen"].is_string() ? doc["listen"].get<std::string>() : "?";
  const std::string saw = "voxl-hitl-vio-server on " + listen + ": ODOMETRY " + fixed(hz, 0) + " Hz (expected " +
                          fixed(expected_hz, 0) + ")";
  const std::string sim_fix = "hitl sim sends ODOMETRY to -i BOARD_IP:14570 unless --no-vio; check --vio-ip / --vio-port";
  if (!(hz > 0)) return make_result(check::kVioOdometry, Verdict::Fail, saw + ": none arrives", sim_fix);
  const double ratio = expected_hz > 0 ? hz / expected_hz : 1.0;
  if (ratio < 0.5) return make_result(check::kVioOdometry, Verdict::Fail, saw, sim_fix);
  if (ratio < 0.8 || ratio > 1.25) return make_result(check::kVioOdometry, Verdict::Warn, saw, "a loaded host or link; " + sim_fix);
  return make_result(check::kVioOdometry, Verdict::Pass, saw);
}

CheckResult vio_server_check(const BoardOutput& is_active) {
  if (!is_active) return vio_skipped(check::kVioServer, is_active.error().message);
  const std::string state = trimmed(is_active.value());
  if (state == "active") return make_result(check::kVioServer, Verdict::Pass, "systemd: voxl-hitl-vio-server active");
  return make_result(check::kVioServer, Verdict::Fail,
                     "systemd: voxl-hitl-vio-server " + (state.empty() ? std::string("unknown") : "'" + state.substr(0, 60) + "'"),
                     std::string(kStartServer) + "; why it stopped: adb shell journalctl -u voxl-hitl-vio-server -n 20");
}

CheckResult vio_pipe_check(const BoardOutput& mpa_listing) {
  if (!mpa_listing) return vio_skipped(check::kVioPipe, mpa_listing.error().message);
  std::istringstream in(mpa_listing.value());
  std::string name, names;
  while (in >> name) {
    while (!name.empty() && name.back() == '/') name.pop_back();
    if (name == "hitl_vio") return make_result(check::kVioPipe, Verdict::Pass, "/run/mpa/hitl_vio present");
    names += (names.empty() ? "" : " ") + name;
  }
  return make_result(check::kVioPipe, Verdict::Fail,
                     "no hitl_vio in /run/mpa (" + (names.empty() ? std::string("empty") : names.substr(0, 100)) + ")",
                     std::string("voxl-hitl-vio-server makes it: ") + kStartServer + "; then voxl-inspect-pipes lists it");
}

CheckResult vision_hub_check(const BoardOutput& config_text) {
  if (!config_text) return vio_skipped(check::kVisionHub, config_text.error().message);
  const char* fix =
      "set \"en_hitl\": true in /etc/modalai/voxl-vision-hub.conf on the board, then: adb shell systemctl restart voxl-vision-hub";
  const auto doc = nlohmann::json::parse(config_text.value(), nullptr, false, true);
  if (doc.is_discarded() || !doc.is_object())
    return make_result(check::kVisionHub, Verdict::Fail,
                       "/etc/modalai/voxl-vision-hub.conf is not JSON: '" + trimmed(config_text.value()).substr(0, 80) + "'", fix);
  if (!doc.contains("en_hitl")) return make_result(check::kVisionHub, Verdict::Fail, "no en_hitl in voxl-vision-hub.conf", fix);
  if (!doc["en_hitl"].is_boolean() || !doc["en_hitl"].get<bool>())
    return make_result(check::kVisionHub, Verdict::Fail, "en_hitl is " + doc["en_hitl"].dump() + " in voxl-vision-hub.conf", fix);
  std::string saw = "en_hitl true";
  if (doc.contains("offboard_mode") && doc["offboard_mode"].is_string()) saw += ", offboard_mode " + doc["offboard_mode"].get<std::string>();
  return make_result(check::kVisionHub, Verdict::Pass, saw);
}

}  // namespace hitl::doctor
