// A campaign file (TOML, docs/campaigns.md): the matrix of flights (trajectories x fault cases x
// seeds x speeds), the flight stack they fly against, the per-flight limits and the pass criteria
// on each flight's summary figures. Parsed with toml++; every refusal names the file, the line and
// the key. Paths in the file are relative to the file's folder.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "engine/faults/fault_spec.h"
#include "engine/px4/px4_build.h"
#include "engine/px4/px4_process.h"

namespace hitl::campaign {

/// Growing things are bounded: a file, an axis, the matrix.
inline constexpr std::size_t kMaxCampaignFileBytes = 1 << 20;
inline constexpr std::size_t kMaxAxisValues = 256;
inline constexpr std::size_t kMaxFlights = 10000;

/// The flight stack the flights fly against: the emulated board (hitl target, in the flight's
/// process), or PX4 SITL that each flight starts, owns and stops as `hitl sim --px4 DIR` does.
enum class Stack { Target, Px4 };
const char* to_string(Stack stack);

/// stack = "px4": the PX4 SITL build every flight starts (`px4 = "DIR"`, or `--px4 DIR`) and the
/// parameters it is given over the vehicle's (`px4_params = { NAME = value }`, as --px4-param).
struct Px4Stack {
  std::string dir_as_written;  ///< px4 = "DIR" as the file wrote it; empty: the file names none (--px4 DIR must)
  std::string dir;             ///< resolved against the campaign file's folder
  int line = 0;                ///< the line of px4 = (or of stack = when the file names no DIR)
  std::vector<px4::Px4Param> params;   ///< in the file's order
  std::optional<px4::Px4Build> build;  ///< found by find_campaign_px4(), before any flight
};

/// A named fault case: the faults one flight starts with (empty: "none").
struct FaultCase {
  std::string name;
  std::vector<std::string> specs;       ///< inline `--fault` specs as written (canonical text in `faults`)
  std::string scenario;                 ///< a scenario file (resolved path), or empty
  std::string scenario_as_written;      ///< the scenario path as the file wrote it (part of the flight's id)
  std::vector<faults::FaultSpec> faults;  ///< parsed: the specs, then the scenario's events
};

/// A trajectory axis value: the path as written (part of the flight's id) and resolved.
struct TrajectoryValue {
  std::string name;         ///< the file's stem: "square"
  std::string as_written;   ///< "../square.json"
  std::string path;         ///< resolved against the campaign file's folder
};

/// How a criterion compares the figure with its limit.
enum class Comparison { AtMost, AtLeast, Equals };
const char* to_string(Comparison comparison);

/// A pass criterion: a named threshold on one figure of the flight's summary (a dotted path into
/// its JSON: "trajectory.rms_m", "landing.touchdowns", "loop_latency.p99_us", "armed").
struct Criterion {
  std::string name;
  std::string figure;
  Comparison comparison = Comparison::AtMost;
  double limit = 0;                 ///< AtMost, AtLeast, Equals of a number
  std::optional<bool> equals_bool;  ///< Equals of a true/false figure
  std::optional<std::string> equals_text;  ///< Equals of a text figure ("stack.landed_state" == "on_ground")
  int line = 0;                     ///< where the file defines it
};

/// What an expectation looks for in the flight's events (the recording read back: engine/report).
enum class ExpectKind {
  Statustext,  ///< a STATUSTEXT from the flight stack whose text matches `pattern`
  Mode,        ///< the flight stack entering the mode named `pattern` ("Land", "Hold", "Position")
  Event,       ///< any event ("armed", "disarmed", "mode Land", a STATUSTEXT from anyone) matching `pattern`
};
const char* to_string(ExpectKind kind);
inline constexpr std::size_t kMaxPatternChars = 200;

/// A named expectation on what the flight stack does: an event, at or after a fault's first start
/// (after_fault) and within within_s of it (or of the flight's start).
struct Expectation {
  std::string name;
  ExpectKind kind = ExpectKind::Statustext;
  std::string pattern;             ///< a regular expression (ECMAScript, found anywhere in the text); Mode: the name
  std::string after_fault;         ///< a fault's name ("gps-loss"); flights without it do not judge this
  std::optional<double> within_s;  ///< at most this long after the fault's start (or the flight's start)
  int line = 0;
};

struct Campaign {
  std::string file;          ///< the path it was read from (as given)
  std::string name;          ///< [campaign] name
  Stack stack = Stack::Target;
  std::optional<Px4Stack> px4;  ///< with stack = "px4"
  double time_limit_s = 300;  ///< [campaign] time_limit_s: wall clock per flight; past it the flight is killed
  double sim_limit_s = 0;     ///< [campaign] sim_limit_s: simulated seconds per flight (0: until the trajectory ends)
  bool report = false;        ///< [campaign] report: the report page per flight (hitl report)
  std::vector<TrajectoryValue> trajectories;
  std::vector<FaultCase> fault_cases;
  std::vector<uint64_t> seeds;
  std::vector<double> speeds;
  std::vector<Criterion> criteria;
  std::vector<Expectation> expectations;
};

/// Parses a campaign file's text; `path` names it in messages and anchors its relative paths.
/// Refused (ErrorKind::Input): TOML syntax, an unknown key, a bad or missing value, a fault spec
/// or scenario the fault catalogue refuses, an unknown figure, an empty matrix; each message
/// "FILE:LINE: KEY: problem".
Expected<Campaign> parse_campaign(const std::string& text, const std::string& path, const faults::Suggest& suggest = {});
/// Reads and parses the file (bounded).
Expected<Campaign> load_campaign(const std::string& path, const faults::Suggest& suggest = {});

/// stack = "px4": finds the PX4 build the flights start, `override_dir` (--px4 DIR) when given, else
/// the file's px4 = "DIR", and keeps it in campaign.px4->build. An input Error saying what is missing
/// in hitl sim --px4's words, naming where the DIR came from ("--px4: 'DIR' is not a PX4 SITL
/// build: ...", "FILE:LINE: campaign.px4: ..."), or that neither names one; a build without
/// lockstep is refused too. With stack = "target", an override is a usage Error.
Status find_campaign_px4(Campaign& campaign, const std::string& override_dir);
/// The flight stack's version: PX4's ("v1.16.0") once found; "" for the emulated board.
std::string stack_version(const Campaign& campaign);

/// The figures a criterion may name: every number, true/false or text leaf of a flight's summary
/// (flight_summary.h), as dotted paths.
std::vector<std::string> criterion_figures();

}  // namespace hitl::campaign
