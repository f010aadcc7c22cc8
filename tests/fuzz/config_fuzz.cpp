// libFuzzer target for the configuration files people edit by hand: vehicle and world JSON
// (parsed over the x500 and the default world, then validated; the vehicle file with the sensor
// units' sections, which must read back as written) and the TOML of `--config`
// (CLI11's reader, as hitl runs it). The first byte picks the parser, the rest is the file.
#include <CLI/CLI.hpp>

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string_view>

#include "engine/model/config_json.h"
#include "engine/sensors/vehicle_file.h"
#include "tests/fuzz/fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* bytes, std::size_t size) {
  if (size == 0) return 0;
  const std::string_view text(reinterpret_cast<const char*>(bytes + 1), size - 1);
  switch (bytes[0] % 3) {
    case 0: {
      auto v = hitl::sensors::parse_vehicle_file(text, "vehicle.json");
      if (v) {
        FUZZ_CHECK(hitl::model::validate(v->vehicle).ok());
        FUZZ_CHECK(hitl::sensors::parse_vehicle_file(hitl::sensors::to_json_text(*v), "again.json").ok());
      } else {
        FUZZ_CHECK(!v.error().message.empty());
      }
      break;
    }
    case 1: {
      auto w = hitl::model::parse_world_config(text, "world.json");
      if (w) FUZZ_CHECK(hitl::model::validate(*w).ok());
      else FUZZ_CHECK(!w.error().message.empty());
      break;
    }
    default: {
      std::istringstream in{std::string(text)};
      try {
        CLI::ConfigTOML toml;
        const auto items = toml.from_config(in);
        for (const auto& item : items) FUZZ_CHECK(item.name.size() <= text.size() + 1);
      } catch (const CLI::Error&) {
        // a refused file is an answer
      }
    }
  }
  return 0;
}
