// libFuzzer target for `hitl campaign run FILE`: the campaign file's parser (toml++ and every key's
// checks), then what parses expanded into flights. A refusal is an input error naming the file
// (its message under 4 KiB); an accepted file has a name, a non-empty matrix of at most kMaxFlights
// flights, each with a 12-hex-digit id and a name of its own. The input is the whole file, read as
// if it were <tmp>/campaigns/c.toml beside the example trajectories (so "../hover.json" resolves);
// an input naming a device or /proc file is skipped (a trajectory path there could block the read).
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "engine/campaign/campaign_file.h"
#include "engine/campaign/flight.h"
#include "tests/fuzz/fuzz_check.h"

namespace {

/// The folder the campaign "is in", with a trajectory of each example name and a scenario.
const std::string& campaign_path() {
  static const std::string path = [] {
    const auto dir = std::filesystem::temp_directory_path() / ("hitl-campaign-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir / "campaigns");
    std::filesystem::create_directories(dir / "scenarios");
    const char* hover = R"({"waypoints": [{"t": 0, "x": 0, "y": 0, "z": 2, "yaw": 0}, {"t": 4, "x": 0, "y": 0, "z": 2, "yaw": 0}]})";
    for (const char* name : {"hover.json", "square.json", "figure-eight.json"}) std::ofstream(dir / name) << hover;
    std::ofstream(dir / "scenarios" / "gps-motor.json") << R"({"events": [{"at_s": 3, "fault": "gps-loss", "duration_s": 2}]})";
    return (dir / "campaigns" / "c.toml").string();
  }();
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* bytes, std::size_t size) {
  using namespace hitl::campaign;
  const std::string text(reinterpret_cast<const char*>(bytes), size);
  for (const char* device : {"/dev", "/proc", "/sys"})
    if (text.find(device) != std::string::npos) return 0;
  const std::string& path = campaign_path();
  auto c = parse_campaign(text, path);
  if (!c) {
    FUZZ_CHECK(c.error().kind == hitl::ErrorKind::Input);
    FUZZ_CHECK(c.error().message.rfind(path, 0) == 0);
    FUZZ_CHECK(c.error().message.size() < 4096);
    return 0;
  }
  FUZZ_CHECK(!c->name.empty());
  const auto flights = expand(*c);
  FUZZ_CHECK(!flights.empty() && flights.size() <= kMaxFlights);
  std::set<std::string> names;
  for (std::size_t i = 0; i < flights.size(); ++i) {
    FUZZ_CHECK(flights[i].index == i);
    FUZZ_CHECK(flights[i].id.size() == 12 && flights[i].id.find_first_not_of("0123456789abcdef") == std::string::npos);
    FUZZ_CHECK(names.insert(flights[i].name).second);
  }
  return 0;
}
