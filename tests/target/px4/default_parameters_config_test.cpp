// voxl-px4-hitl-set-default-parameters.config is generated from base/contract/hitl-defaults.params
// (the data file `hitl params reset` uses): every value in it equals the .params file's.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "engine/vehicle/param_notes.h"
#include "engine/vehicle/params_file.h"
#include "tests/support/process.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;

const std::string kParamsFile = std::string(HITL_SOURCE_DIR) + "/base/contract/hitl-defaults.params";

struct ConfigLine {
  std::string name;
  std::string value;
  bool if_present = false;  ///< `param set-if-present`: a parameter some firmware lacks
};

std::vector<ConfigLine> read_config(const std::string& path, std::vector<std::string>& problems) {
  std::ifstream in(path);
  std::vector<ConfigLine> out;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    std::string param, set, name, value, extra;
    if (!(words >> param >> set >> name >> value) || param != "param" || (set != "set" && set != "set-if-present") ||
        (words >> extra)) {
      problems.push_back("not 'param set[-if-present] NAME VALUE': " + line);
      continue;
    }
    out.push_back({name, value, set == "set-if-present"});
  }
  return out;
}

TEST(DefaultParametersConfig, EveryValueEqualsTheParamsFile) {
  auto params = vehicle::load_params_file(kParamsFile);
  ASSERT_TRUE(params.ok()) << params.error().message;
  std::vector<std::string> problems;
  const auto config = read_config(HITL_PX4_DEFAULTS_CONFIG, problems);
  EXPECT_TRUE(problems.empty()) << problems.front();
  ASSERT_EQ(config.size(), params->size());
  for (std::size_t i = 0; i < config.size(); ++i) {
    const vehicle::Param& p = params.value()[i];
    SCOPED_TRACE(p.name);
    EXPECT_EQ(config[i].name, p.name);
    // set-if-present exactly for the parameters hitl-defaults.params notes as absent somewhere.
    EXPECT_EQ(config[i].if_present, vehicle::find_absent_note(p.name) != nullptr);
    // The value as PX4's `param set` reads it, typed as the .params file says.
    std::ostringstream line;
    line << "1\t1\t" << config[i].name << "\t" << config[i].value << "\t" << static_cast<int>(p.value.type) << "\n";
    auto reparsed = vehicle::parse_params(line.str(), "generated config");
    ASSERT_TRUE(reparsed.ok()) << reparsed.error().message;
    EXPECT_EQ(reparsed.value().at(0).value, p.value) << config[i].value;
  }
  // And it is the set `hitl params reset` pushes.
  EXPECT_EQ(params->size(), vehicle::hitl_default_params().size());
}

TEST(DefaultParametersConfig, TheGeneratorRefusesABadParamsFile) {
  const std::string dir = test::temp_dir();
  const std::string bad = dir + "/bad.params";
  std::ofstream(bad) << "1\t1\tSYS_AUTOSTART\t1001\t6\n1\t1\tCOM_ARM_EKF_POS\tone\t9\n";
  test::Process p({HITL_CMAKE_COMMAND, "-DINPUT=" + bad, "-DOUTPUT=" + dir + "/out.config", "-P",
                   std::string(HITL_SOURCE_DIR) + "/target/px4/scripts/params_to_config.cmake"});
  EXPECT_NE(p.wait(60s), 0);
  EXPECT_NE(p.err().find("COM_ARM_EKF_POS: value 'one' is not a"), std::string::npos) << p.err();
  EXPECT_FALSE(std::filesystem::exists(dir + "/out.config"));
}

}  // namespace
}  // namespace hitl
