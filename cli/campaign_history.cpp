#include "cli/campaign_history.h"

#include <cstdio>
#include <iostream>

#include "cli/commands.h"
#include "engine/campaign/history.h"

namespace hitl::cli {

Expected<std::string> history_path(const std::string& given) {
  if (!given.empty()) return given;
  auto path = campaign::default_history_path();
  if (!path) return path.error().prefixed("--history: ");
  return path;
}

Expected<std::string> run_history(bool no_history, const std::string& given) {
  if (no_history) return std::string();
  return history_path(given);
}

int run_history_command(const GlobalOptions& g, const CampaignHistoryOptions& o) {
  auto path = history_path(o.history);
  if (!path) return log_error("campaign", path.error());
  std::string name = o.campaign;
  if (name.empty()) {
    auto names = campaign::history_campaigns(*path);
    if (!names) return log_error("campaign", names.error());
    if (names->empty()) return log_error("campaign", Error::input("history " + *path + ": no runs yet"));
    name = names->front();
  }
  auto h = campaign::read_history(*path, name, o.last_runs);
  if (!h) return log_error("campaign", h.error());
  bool regression = false;
  for (const auto& t : h->trends) regression = regression || t.regression;
  if (g.json) {
    nlohmann::json trends = nlohmann::json::array();
    for (const auto& t : h->trends) {
      nlohmann::json points = nlohmann::json::array();
      for (const auto& p : t.points)
        points.push_back({{"run", p.run}, {"label", p.label}, {"stack_version", p.stack_version}, {"started_utc", p.started_utc}, {"flights", p.flights},
                          {"failed", p.failed}, {"mean", p.flights > 0 ? nlohmann::json(p.mean) : nlohmann::json(nullptr)},
                          {"worst", p.flights > 0 ? nlohmann::json(p.worst) : nlohmann::json(nullptr)}});
      trends.push_back({{"criterion", t.criterion}, {"figure", t.figure}, {"limit", t.limit}, {"points", points},
                        {"regression", t.regression}, {"verdict", t.verdict}});
    }
    print_json_line({{"type", "summary"}, {"campaign", h->campaign}, {"history", *path}, {"runs", h->runs},
                     {"regression", regression}, {"trends", trends}});
  } else {
    std::cout << "campaign " << h->campaign << ": " << h->runs << " runs in " << *path << "\n";
    for (const auto& t : h->trends) {
      std::cout << "\n" << t.criterion << " (" << t.figure << " " << t.limit << ")\n";
      for (const auto& p : t.points) {
        char line[256];
        if (p.flights > 0)
          std::snprintf(line, sizeof line, "  run %-4lld %-20s %-16s mean %-10.4g worst %-10.4g failed %zu", static_cast<long long>(p.run),
                        p.started_utc.c_str(), p.label.empty() ? "-" : p.label.c_str(), p.mean, p.worst, p.failed);
        else
          std::snprintf(line, sizeof line, "  run %-4lld %-20s %-16s failed %zu", static_cast<long long>(p.run), p.started_utc.c_str(),
                        p.label.empty() ? "-" : p.label.c_str(), p.failed);
        std::cout << line << (p.stack_version.empty() ? "" : "  (PX4 " + p.stack_version + ")") << '\n';
      }
      std::cout << "  " << t.verdict << '\n';
    }
  }
  return regression ? kExitFailed : kExitOk;
}

}  // namespace hitl::cli
