#include "engine/doctor/apps_shell.h"


namespace hitl::doctor {
namespace {

const char* kNeedsAdb = "needs a shell on the board's apps processor: run hitl doctor --adb (PX4's shell cannot run it)";

}  // namespace

AppsShell AppsShell::adb(net::Adb adb) {
  AppsShell s;
  s.adb_.emplace(std::move(adb));
  return s;
}

AppsShell AppsShell::px4(Px4Shell shell) {
  AppsShell s;
  s.px4_ = std::move(shell);
  return s;
}

AppsShell AppsShell::none(std::string why) {
  AppsShell s;
  s.none_ = std::move(why);
  return s;
}

Expected<std::string> AppsShell::run(const std::string& command, bool px4_answers) const {
  if (adb_) {
    auto r = adb_->shell(command);
    if (!r) return Error::failed("adb shell " + command + ": " + r.error().message);
    return r->out + r->err;  // systemctl is-active exits 3 for "inactive": the text is the answer
  }
  if (!px4_) return Error::failed(none_.empty() ? std::string(kNeedsAdb) : none_);
  if (!px4_answers) return Error::failed(kNeedsAdb);
  auto r = px4_(command);
  if (!r) return Error::failed("PX4's shell: " + r.error().message);
  if (r->find("command not found") != std::string::npos) return Error::failed(kNeedsAdb);
  return r;
}

}  // namespace hitl::doctor
