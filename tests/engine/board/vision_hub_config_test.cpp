#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "engine/board/vision_hub_config.h"

namespace hitl::board {
namespace {

TEST(VisionHubConfig, SetsTheSpecsKeysAndKeepsEveryOtherKeyInItsOrder) {
  const std::string original =
      "{\n\t\"config_file_version\":\t1,\n\t\"en_localhost_mavlink_udp\":\tfalse,\n\t\"vio_pipe\":\t\"qvio\",\n"
      "\t\"offboard_mode\":\t\"off\",\n\t\"fixed_frame_filter_len\":\t5,\n\t\"nested\":\t{\"a\": [1, 2]}\n}\n";
  auto edit = edit_vision_hub_config(original);
  ASSERT_TRUE(edit) << edit.error().message;
  const auto j = nlohmann::ordered_json::parse(edit->text);
  std::vector<std::string> keys;
  for (const auto& [k, v] : j.items()) keys.push_back(k);
  EXPECT_EQ(keys, (std::vector<std::string>{"config_file_version", "en_localhost_mavlink_udp", "vio_pipe", "offboard_mode",
                                            "fixed_frame_filter_len", "nested", "en_vio", "en_hitl"}));
  EXPECT_EQ(j["en_hitl"], true);
  EXPECT_EQ(j["en_vio"], false);
  EXPECT_EQ(j["offboard_mode"], "vfc");
  EXPECT_EQ(j["vio_pipe"], "qvio");
  EXPECT_EQ(j["nested"]["a"][1], 2);
  EXPECT_EQ(j["fixed_frame_filter_len"], 5);
  ASSERT_EQ(edit->keys.size(), 4u);
  EXPECT_EQ(edit->keys[0].key, "en_vio");
  EXPECT_EQ(edit->keys[0].from, "absent");
  EXPECT_EQ(edit->keys[3].from, "\"off\"");
  EXPECT_EQ(edit->keys[3].to, "\"vfc\"");
  EXPECT_TRUE(edit->changes());
  // Edited twice: nothing more changes.
  auto again = edit_vision_hub_config(edit->text);
  ASSERT_TRUE(again);
  EXPECT_FALSE(again->changes());
  EXPECT_EQ(again->text, edit->text);
}

TEST(VisionHubConfig, NoFileGivesTheSpecsFourKeys) {
  auto edit = edit_vision_hub_config("");
  ASSERT_TRUE(edit);
  EXPECT_EQ(nlohmann::json::parse(edit->text),
            nlohmann::json::parse(R"({"en_vio": false, "vio_pipe": "qvio", "en_hitl": true, "offboard_mode": "vfc"})"));
}

TEST(VisionHubConfig, NotJsonOrNotAnObjectIsAnInputErrorNamingTheFile) {
  for (const char* text : {"{\"en_hitl\": tru", "[1, 2]", "not json"}) {
    auto edit = edit_vision_hub_config(text);
    ASSERT_FALSE(edit) << text;
    EXPECT_EQ(edit.error().kind, ErrorKind::Input);
    EXPECT_NE(edit.error().message.find("/etc/modalai/voxl-vision-hub.conf"), std::string::npos) << edit.error().message;
  }
}

TEST(VisionHubConfig, VioServerConfigIsTheSpecs) {
  EXPECT_EQ(nlohmann::json::parse(vio_server_config_text()), nlohmann::json::parse(R"({"receiver_ip": "0.0.0.0", "receiver_port": 14570})"));
}

}  // namespace
}  // namespace hitl::board
