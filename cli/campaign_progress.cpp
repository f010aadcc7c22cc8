#include "cli/campaign_progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iostream>

#include "cli/commands.h"

namespace hitl::cli {

void FlightEvents::on_event(const target::BoardEvent& e) {
  if (e.severity == Severity::Info && g_.verbosity == 0) return;
  std::lock_guard<std::mutex> lock(mutex_);
  std::cerr << "hitl campaign: board: " << e.text << '\n';
}

void FlightEvents::on_event(const hil::SessionEvent& e) {
  if (e.severity == hil::Severity::Info && g_.verbosity == 0) return;
  std::lock_guard<std::mutex> lock(mutex_);
  std::cerr << "hitl campaign: " << e.text << '\n';
}

std::string duration_text(double s) {
  char text[32];
  if (s >= 3600) std::snprintf(text, sizeof text, "%dh%02dm", static_cast<int>(s / 3600), static_cast<int>(std::fmod(s, 3600) / 60));
  else if (s >= 60) std::snprintf(text, sizeof text, "%dm%02ds", static_cast<int>(s / 60), static_cast<int>(std::fmod(s, 60)));
  else std::snprintf(text, sizeof text, "%.0fs", s);
  return text;
}

RunPrinter::RunPrinter(const GlobalOptions& g, std::string name) : g_(g), name_(std::move(name)), tty_(::isatty(STDERR_FILENO) == 1) {}

void RunPrinter::on_started(const campaign::Flight& f, pid_t pid) {
  if (g_.json)
    print_json_line({{"type", "status"}, {"event", "started"}, {"index", f.index}, {"id", f.id}, {"name", f.name}, {"pid", pid}});
}

void RunPrinter::on_finished(const campaign::Flight& f, const campaign::FlightResult& r) {
  if (g_.json) {
    nlohmann::json failures = nlohmann::json::array();
    for (const auto& v : r.verdicts)
      if (!v.ok) failures.push_back(v.criterion + ": " + v.message);
    print_json_line({{"type", "status"}, {"event", "finished"}, {"index", f.index}, {"id", f.id}, {"name", f.name},
                     {"outcome", r.outcome}, {"reason", r.reason}, {"failures", failures}, {"summary_line", r.summary_line}});
    return;
  }
  if (g_.quiet && r.outcome == "passed") return;
  clear_line();
  std::string line = "hitl campaign: " + r.outcome + "  " + r.summary_line;
  for (const auto& v : r.verdicts)
    if (!v.ok && v.criterion != "flown") line += "\n    " + v.criterion + ": " + v.message;
  std::cerr << line << '\n';
}

void RunPrinter::on_progress(const campaign::Progress& p) {
  if (g_.json) {
    print_json_line({{"type", "status"}, {"event", "progress"}, {"total", p.total}, {"done", p.done}, {"passed", p.passed},
                     {"failed", p.failed}, {"running", p.running}, {"kept", p.kept}, {"elapsed_s", p.elapsed_s},
                     {"eta_s", p.eta_s ? nlohmann::json(*p.eta_s) : nlohmann::json(nullptr)}});
    return;
  }
  if (!tty_ || g_.quiet) return;
  char line[200];
  std::snprintf(line, sizeof line, "campaign %s: %zu/%zu done, %zu failed, %zu running, %s elapsed, ETA %s", name_.c_str(),
                p.done, p.total, p.failed, p.running, duration_text(p.elapsed_s).c_str(),
                p.eta_s ? duration_text(*p.eta_s).c_str() : "?");
  std::cerr << "\r\033[K" << line << std::flush;
  drawn_ = true;
}

void RunPrinter::clear_line() {
  if (drawn_) std::cerr << "\r\033[K";
  drawn_ = false;
}

}  // namespace hitl::cli
