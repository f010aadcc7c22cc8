// voxl-hitl-vio-server's configuration file: defaults from the packaged file, errors naming the key.
#include "target/vio-server/vio_server_config.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "base/contract/board_ports.h"
#include "tests/support/process.h"

namespace hitl::vio {
namespace {

std::string error_of(std::string_view text) {
  auto c = parse_config(text, "test.conf");
  return c.ok() ? std::string("accepted") : c.error().message;
}

TEST(VioServerConfig, DefaultsAreTheSpecsAndTheBoardsVioPort) {
  const VioServerConfig d = default_config();
  EXPECT_EQ(d.receiver_ip, "0.0.0.0");
  EXPECT_EQ(d.receiver_port, kBoardVioPort);  // the port hitl sim sends ODOMETRY to
}

TEST(VioServerConfig, PackagedFileIsTheCompiledInDefault) {
  std::ifstream in(std::string(HITL_SOURCE_DIR) + "/target/vio-server/voxl-hitl-vio-server.conf");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), default_config_text());
}

TEST(VioServerConfig, ReadsBothKeysAndKeepsDefaultsForMissingOnes) {
  auto c = parse_config(R"({"receiver_ip": "127.0.0.1", "receiver_port": 15000})", "test.conf");
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_EQ(c->receiver_ip, "127.0.0.1");
  EXPECT_EQ(c->receiver_port, 15000);
  c = parse_config(R"({"receiver_port": 15001})", "test.conf");
  ASSERT_TRUE(c.ok());
  EXPECT_EQ(c->receiver_ip, "0.0.0.0");
  c = parse_config("{}", "test.conf");
  ASSERT_TRUE(c.ok());
  EXPECT_EQ(c->receiver_port, default_config().receiver_port);
}

TEST(VioServerConfig, ErrorsNameTheFileAndTheKey) {
  EXPECT_EQ(error_of(R"({"receiver_port": "14570"})").rfind("test.conf: \"receiver_port\" must be an integer", 0), 0u);
  EXPECT_NE(error_of(R"({"receiver_port": 0})").find("\"receiver_port\""), std::string::npos);
  EXPECT_NE(error_of(R"({"receiver_port": 65536})").find("\"receiver_port\""), std::string::npos);
  EXPECT_NE(error_of(R"({"receiver_port": 14570.5})").find("\"receiver_port\""), std::string::npos);
  // A number beyond a double's range is a named error, not an uncaught exception (abort).
  EXPECT_NE(error_of(R"({"receiver_port": 1e400})").find("not valid JSON"), std::string::npos);
  EXPECT_EQ(error_of(R"({"receiver_ip": "localhost"})").rfind("test.conf: \"receiver_ip\" must be an IPv4 address", 0), 0u);
  EXPECT_NE(error_of(R"({"receiver_ip": 1234})").find("\"receiver_ip\" must be a string"), std::string::npos);
  EXPECT_NE(error_of(R"({"reciever_port": 14570})").find("\"reciever_port\" is not a key"), std::string::npos);
  EXPECT_NE(error_of(R"([1, 2])").find("expected a JSON object"), std::string::npos);
  EXPECT_NE(error_of(R"({"receiver_port": 14570,})").find("not valid JSON"), std::string::npos);
  EXPECT_NE(error_of("").find("not valid JSON"), std::string::npos);
}

TEST(VioServerConfig, MissingFileIsCreatedWithTheDefaults) {
  const std::string dir = test::temp_dir() + "/etc/modalai";
  const std::string path = dir + "/voxl-hitl-vio-server.conf";
  auto loaded = load_or_create_config(path);
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  EXPECT_TRUE(loaded->created);
  EXPECT_EQ(loaded->config.receiver_port, default_config().receiver_port);
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), default_config_text());
  // The second time it is read, not created.
  loaded = load_or_create_config(path);
  ASSERT_TRUE(loaded.ok());
  EXPECT_FALSE(loaded->created);
}

TEST(VioServerConfig, ABadFileIsAnErrorNamingThePath) {
  const std::string path = test::temp_dir() + "/bad.conf";
  std::ofstream(path) << R"({"receiver_port": -3})";
  auto loaded = load_or_create_config(path);
  ASSERT_FALSE(loaded.ok());
  EXPECT_EQ(loaded.error().message.rfind(path + ": \"receiver_port\"", 0), 0u) << loaded.error().message;
  const std::string dir = test::temp_dir();
  loaded = load_or_create_config(dir);
  ASSERT_FALSE(loaded.ok());
  EXPECT_NE(loaded.error().message.find("is a directory"), std::string::npos);
}

}  // namespace
}  // namespace hitl::vio
