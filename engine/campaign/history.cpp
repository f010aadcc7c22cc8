// The history database through SQLite's C API (Debian's libsqlite3-dev): one file, safe against
// two runs writing at once (a busy timeout), readable by any SQLite tool. Three tables: runs,
// flights (each run's flights and outcomes) and verdicts (each flight's criteria and figures).
#include "engine/campaign/history.h"

#include <sqlite3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>

namespace hitl::campaign {

namespace {

constexpr const char* kSchemaVersion = "2";  ///< 2: runs.stack and runs.stack_version (a history of schema 1 gains them)
constexpr int kBusyTimeout_ms = 10000;

constexpr const char* kSchema = R"(
CREATE TABLE IF NOT EXISTS meta(key TEXT PRIMARY KEY, value TEXT);
CREATE TABLE IF NOT EXISTS runs(id INTEGER PRIMARY KEY AUTOINCREMENT, campaign TEXT NOT NULL, file TEXT, label TEXT,
  started_utc TEXT, wall_s REAL, flights INTEGER, passed INTEGER, failed INTEGER, errors INTEGER, missing INTEGER,
  stopped INTEGER, stack TEXT, stack_version TEXT);
CREATE TABLE IF NOT EXISTS flights(run INTEGER NOT NULL, flight_id TEXT, name TEXT, outcome TEXT, reason TEXT);
CREATE TABLE IF NOT EXISTS verdicts(run INTEGER NOT NULL, flight_id TEXT, criterion TEXT, figure TEXT, limit_text TEXT,
  value REAL, ok INTEGER);
CREATE INDEX IF NOT EXISTS verdicts_run ON verdicts(run);
CREATE INDEX IF NOT EXISTS runs_campaign ON runs(campaign);
)";

struct DbCloser {
  void operator()(sqlite3* db) const { sqlite3_close(db); }
};
using Db = std::unique_ptr<sqlite3, DbCloser>;
struct StmtFinalizer {
  void operator()(sqlite3_stmt* s) const { sqlite3_finalize(s); }
};
using Stmt = std::unique_ptr<sqlite3_stmt, StmtFinalizer>;

Error db_error(const std::string& path, sqlite3* db, const std::string& doing) {
  return Error::unavailable("history " + path + ": " + doing + ": " + (db != nullptr ? sqlite3_errmsg(db) : "out of memory"));
}

Expected<Db> open_db(const std::string& path, bool create) {
  if (create) {
    std::error_code ec;
    const auto parent = std::filesystem::path(path).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent, ec);
    if (ec) return Error::unavailable("history " + path + ": cannot make its folder: " + ec.message());
  } else if (!std::filesystem::exists(path)) {
    return Error::input("history " + path + ": no such file (hitl campaign run writes it; --history FILE names another)");
  }
  sqlite3* raw = nullptr;
  const int flags = create ? SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE : SQLITE_OPEN_READONLY;
  const int rc = sqlite3_open_v2(path.c_str(), &raw, flags, nullptr);
  Db db(raw);
  if (rc != SQLITE_OK) return db_error(path, raw, "cannot open");
  sqlite3_busy_timeout(raw, kBusyTimeout_ms);
  if (create) {
    char* message = nullptr;
    if (sqlite3_exec(raw, kSchema, nullptr, nullptr, &message) != SQLITE_OK) {
      const std::string text = message != nullptr ? message : "?";
      sqlite3_free(message);
      return Error::input("history " + path + ": not a hitl campaign history (" + text + ")");
    }
  }
  // A database of another kind (or another version of this one) is refused, not written into.
  sqlite3_stmt* s = nullptr;
  if (sqlite3_prepare_v2(raw, "SELECT value FROM meta WHERE key = 'schema'", -1, &s, nullptr) != SQLITE_OK)
    return Error::input("history " + path + ": not a hitl campaign history (" + sqlite3_errmsg(raw) + ")");
  Stmt stmt(s);
  if (sqlite3_step(s) == SQLITE_ROW) {
    const auto* v = sqlite3_column_text(s, 0);
    const std::string schema = v != nullptr ? std::string(reinterpret_cast<const char*>(v)) : "?";
    if (schema == "1" && create) {  // schema 1 had no stack: its runs were all against the emulated board
      stmt.reset();
      if (sqlite3_exec(raw,
                       "BEGIN IMMEDIATE; ALTER TABLE runs ADD COLUMN stack TEXT; ALTER TABLE runs ADD COLUMN stack_version TEXT; "
                       "UPDATE runs SET stack = 'target', stack_version = ''; UPDATE meta SET value = '2' WHERE key = 'schema'; COMMIT",
                       nullptr, nullptr, nullptr) != SQLITE_OK) {
        sqlite3_exec(raw, "ROLLBACK", nullptr, nullptr, nullptr);
        return db_error(path, raw, "cannot add the stack to a history of schema 1");
      }
    } else if (schema != kSchemaVersion && schema != "1") {
      return Error::input("history " + path + ": a history of another hitl version (schema " + schema + ")");
    }
  } else if (create) {
    if (sqlite3_exec(raw, "INSERT INTO meta(key, value) VALUES('schema', '2')", nullptr, nullptr, nullptr) != SQLITE_OK)
      return db_error(path, raw, "cannot write");
  }
  return db;
}

Expected<Stmt> prepare(const std::string& path, sqlite3* db, const char* sql) {
  sqlite3_stmt* s = nullptr;
  if (sqlite3_prepare_v2(db, sql, -1, &s, nullptr) != SQLITE_OK) return db_error(path, db, "cannot prepare a statement");
  return Stmt(s);
}

void bind_text(sqlite3_stmt* s, int i, const std::string& text) { sqlite3_bind_text(s, i, text.c_str(), -1, SQLITE_TRANSIENT); }

std::string column_text(sqlite3_stmt* s, int i) {
  const auto* v = sqlite3_column_text(s, i);
  return v != nullptr ? std::string(reinterpret_cast<const char*>(v)) : std::string();
}

std::string number_text(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", v);
  return text;
}

bool at_most(const std::string& limit) { return limit.rfind("<=", 0) == 0; }
bool at_least(const std::string& limit) { return limit.rfind(">=", 0) == 0; }

}  // namespace

Expected<std::string> default_history_path() {
  const char* xdg = std::getenv("XDG_DATA_HOME");
  if (xdg != nullptr && *xdg == '/') return std::string(xdg) + "/hitl/campaigns.sqlite";
  const char* home = std::getenv("HOME");
  if (home != nullptr && *home != '\0') return std::string(home) + "/.local/share/hitl/campaigns.sqlite";
  return Error::usage("no XDG_DATA_HOME or HOME for the campaign history: give --history FILE");
}

Status record_run(const std::string& path, const Campaign& campaign, const std::vector<Flight>& flights,
                  const std::vector<std::optional<FlightResult>>& results, const RunRecord& run) {
  auto db = open_db(path, true);
  if (!db) return db.error();
  sqlite3* d = db->get();
  if (sqlite3_exec(d, "BEGIN IMMEDIATE", nullptr, nullptr, nullptr) != SQLITE_OK) return db_error(path, d, "cannot write");
  std::size_t passed = 0, failed = 0, errors = 0, missing = 0;
  for (const auto& r : results) {
    if (!r) ++missing;
    else if (r->outcome == "passed") ++passed;
    else if (r->outcome == "failed") ++failed;
    else ++errors;
  }
  auto insert_run = prepare(path, d,
                            "INSERT INTO runs(campaign, file, label, started_utc, wall_s, flights, passed, failed, errors, missing, "
                            "stopped, stack, stack_version) VALUES(?,?,?,?,?,?,?,?,?,?,?,?,?)");
  if (!insert_run) return insert_run.error();
  sqlite3_stmt* s = insert_run->get();
  bind_text(s, 1, campaign.name);
  bind_text(s, 2, campaign.file);
  bind_text(s, 3, run.label);
  bind_text(s, 4, run.started_utc);
  sqlite3_bind_double(s, 5, run.wall_s);
  const std::size_t counts[] = {flights.size(), passed, failed, errors, missing};
  for (int i = 0; i < 5; ++i) sqlite3_bind_int64(s, 6 + i, static_cast<sqlite3_int64>(counts[i]));
  sqlite3_bind_int(s, 11, run.stopped ? 1 : 0);
  bind_text(s, 12, to_string(campaign.stack));
  bind_text(s, 13, stack_version(campaign));
  if (sqlite3_step(s) != SQLITE_DONE) return db_error(path, d, "cannot write the run");
  const sqlite3_int64 run_id = sqlite3_last_insert_rowid(d);
  auto insert_flight = prepare(path, d, "INSERT INTO flights(run, flight_id, name, outcome, reason) VALUES(?,?,?,?,?)");
  auto insert_verdict = prepare(path, d,
                                "INSERT INTO verdicts(run, flight_id, criterion, figure, limit_text, value, ok) VALUES(?,?,?,?,?,?,?)");
  if (!insert_flight) return insert_flight.error();
  if (!insert_verdict) return insert_verdict.error();
  for (const auto& f : flights) {
    const auto& r = results[f.index];
    sqlite3_stmt* fs = insert_flight->get();
    sqlite3_reset(fs);
    sqlite3_bind_int64(fs, 1, run_id);
    bind_text(fs, 2, f.id);
    bind_text(fs, 3, f.name);
    bind_text(fs, 4, r ? r->outcome : "missing");
    bind_text(fs, 5, r ? r->reason : "");
    if (sqlite3_step(fs) != SQLITE_DONE) return db_error(path, d, "cannot write a flight");
    if (!r) continue;
    for (const auto& v : r->verdicts) {
      sqlite3_stmt* vs = insert_verdict->get();
      sqlite3_reset(vs);
      sqlite3_bind_int64(vs, 1, run_id);
      bind_text(vs, 2, f.id);
      bind_text(vs, 3, v.criterion);
      bind_text(vs, 4, v.figure);
      bind_text(vs, 5, v.limit);
      if (v.value.is_number()) sqlite3_bind_double(vs, 6, v.value.get<double>());
      else if (v.value.is_boolean()) sqlite3_bind_double(vs, 6, v.value.get<bool>() ? 1.0 : 0.0);
      else sqlite3_bind_null(vs, 6);
      sqlite3_bind_int(vs, 7, v.ok ? 1 : 0);
      if (sqlite3_step(vs) != SQLITE_DONE) return db_error(path, d, "cannot write a verdict");
    }
  }
  if (sqlite3_exec(d, "COMMIT", nullptr, nullptr, nullptr) != SQLITE_OK) return db_error(path, d, "cannot commit");
  return Ok{};
}

Expected<std::vector<std::string>> history_campaigns(const std::string& path) {
  auto db = open_db(path, false);
  if (!db) return db.error();
  auto q = prepare(path, db->get(), "SELECT campaign, MAX(id) AS last FROM runs GROUP BY campaign ORDER BY last DESC");
  if (!q) return q.error();
  std::vector<std::string> out;
  while (sqlite3_step(q->get()) == SQLITE_ROW) out.push_back(column_text(q->get(), 0));
  return out;
}

void judge_trend(Trend& t) {
  if (t.points.size() < 3) {
    t.verdict = "fewer than 3 runs: no trend yet";
    return;
  }
  const bool by_failures = !at_most(t.limit) && !at_least(t.limit);
  // "Worse" as a larger number: the mean of a "<=" criterion, minus the mean of a ">=" one, the failures of "==".
  auto badness = [&](const TrendPoint& p) {
    if (by_failures) return static_cast<double>(p.failed);
    return at_most(t.limit) ? p.mean : -p.mean;
  };
  const TrendPoint& latest = t.points.back();
  if (!by_failures && latest.flights == 0) {
    t.verdict = "the latest run measured no " + t.figure;
    return;
  }
  double low = 1e300, high = -1e300, sum = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i + 1 < t.points.size(); ++i) {
    if (!by_failures && t.points[i].flights == 0) continue;
    const double b = badness(t.points[i]);
    low = std::min(low, b);
    high = std::max(high, b);
    sum += b;
    ++n;
  }
  if (n < 2) {
    t.verdict = "fewer than 2 earlier runs measured it: no trend yet";
    return;
  }
  const double before = sum / static_cast<double>(n), spread = high - low, worse_by = badness(latest) - before;
  auto shown = [&](double b) { return number_text(by_failures || at_most(t.limit) ? b : -b); };
  const std::string what = by_failures ? "failures " : "mean ";
  const std::string range = shown(by_failures || at_most(t.limit) ? low : high) + ".." + shown(by_failures || at_most(t.limit) ? high : low);
  t.regression = worse_by > spread && worse_by > 1e-12;
  t.verdict = (t.regression ? "REGRESSION: " : worse_by > 1e-12 ? "within the spread: " : "steady or better: ") + what +
              shown(badness(latest)) + " against " + shown(before) + " (" + range + ") over the " + std::to_string(n) +
              " runs before" + (t.regression ? ", worse by more than their spread " + number_text(spread) : "");
}

Expected<History> read_history(const std::string& path, const std::string& campaign, std::size_t last_runs) {
  auto db = open_db(path, false);
  if (!db) return db.error();
  sqlite3* d = db->get();
  History h;
  h.campaign = campaign;
  auto count = prepare(path, d, "SELECT COUNT(*) FROM runs WHERE campaign = ?");
  if (!count) return count.error();
  bind_text(count->get(), 1, campaign);
  if (sqlite3_step(count->get()) == SQLITE_ROW) h.runs = static_cast<std::size_t>(sqlite3_column_int64(count->get(), 0));
  if (h.runs == 0) return Error::input("history " + path + ": no runs of campaign \"" + campaign + "\"");
  // A history of schema 1, read only, has no stack_version: its runs flew the emulated board.
  auto columns = prepare(path, d, "SELECT COUNT(*) FROM pragma_table_info('runs') WHERE name = 'stack_version'");
  if (!columns) return columns.error();
  const bool has_version = sqlite3_step(columns->get()) == SQLITE_ROW && sqlite3_column_int(columns->get(), 0) > 0;
  auto runs = prepare(path, d,
                      has_version ? "SELECT id, label, started_utc, stack_version FROM runs WHERE campaign = ? ORDER BY id DESC LIMIT ?"
                                  : "SELECT id, label, started_utc, '' FROM runs WHERE campaign = ? ORDER BY id DESC LIMIT ?");
  if (!runs) return runs.error();
  bind_text(runs->get(), 1, campaign);
  sqlite3_bind_int64(runs->get(), 2, static_cast<sqlite3_int64>(std::max<std::size_t>(last_runs, 2)));
  std::vector<TrendPoint> run_points;
  while (sqlite3_step(runs->get()) == SQLITE_ROW) {
    TrendPoint p;
    p.run = sqlite3_column_int64(runs->get(), 0);
    p.label = column_text(runs->get(), 1);
    p.started_utc = column_text(runs->get(), 2);
    p.stack_version = column_text(runs->get(), 3);
    run_points.push_back(p);
  }
  std::reverse(run_points.begin(), run_points.end());  // oldest first
  auto per_run = prepare(path, d,
                         "SELECT criterion, figure, limit_text, COUNT(value), SUM(ok = 0), AVG(value), MAX(value), MIN(value), "
                         "MIN(rowid) AS first FROM verdicts WHERE run = ? GROUP BY criterion ORDER BY first");
  if (!per_run) return per_run.error();
  std::map<std::string, std::size_t> index;  // criterion -> trends[i], in the latest run's order
  for (auto it = run_points.rbegin(); it != run_points.rend(); ++it) {  // latest first: its criteria lead
    sqlite3_stmt* s = per_run->get();
    sqlite3_reset(s);
    sqlite3_bind_int64(s, 1, it->run);
    while (sqlite3_step(s) == SQLITE_ROW) {
      const std::string criterion = column_text(s, 0);
      if (index.count(criterion) == 0) {
        if (it != run_points.rbegin()) continue;  // a criterion the latest run no longer has
        index[criterion] = h.trends.size();
        Trend t;
        t.criterion = criterion;
        t.figure = column_text(s, 1);
        t.limit = column_text(s, 2);
        h.trends.push_back(std::move(t));
      }
      TrendPoint p = *it;
      p.flights = static_cast<std::size_t>(sqlite3_column_int64(s, 3));
      p.failed = static_cast<std::size_t>(sqlite3_column_int64(s, 4));
      p.mean = sqlite3_column_double(s, 5);
      const std::string limit = column_text(s, 2);
      p.worst = at_least(limit) ? sqlite3_column_double(s, 7) : sqlite3_column_double(s, 6);
      auto& points = h.trends[index[criterion]].points;
      points.insert(points.begin(), p);  // runs come latest first: each earlier one goes in front
    }
  }
  for (auto& t : h.trends) judge_trend(t);
  return h;
}

}  // namespace hitl::campaign
