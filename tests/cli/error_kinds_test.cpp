// Exit codes come from error kinds in one place (cli/common_options.h, exit_code()), and engine calls
// give the kinds the exit-code table needs: a file that cannot be read or does not parse is Input, a
// port in use is Unavailable (both 2), no answer is Failed (1).
#include <gtest/gtest.h>

#include "cli/common_options.h"
#include "engine/net/link_spec.h"
#include "engine/mavlink/dialect_xml.h"
#include "engine/model/config_json.h"
#include "engine/net/socket_address.h"
#include "engine/net/tcp_links.h"
#include "engine/net/udp_endpoint.h"
#include "engine/vehicle/params_file.h"
#include "engine/vehicle/trajectory.h"

namespace hitl {
namespace {

using cli::exit_code;

TEST(ExitCodeFromKind, TheTable) {
  EXPECT_EQ(exit_code(ErrorKind::Usage), cli::kExitUsage);
  EXPECT_EQ(exit_code(ErrorKind::Input), cli::kExitUsage);
  EXPECT_EQ(exit_code(ErrorKind::Unavailable), cli::kExitUsage);
  EXPECT_EQ(exit_code(ErrorKind::Failed), cli::kExitFailed);
  EXPECT_EQ(exit_code(Error{"no HEARTBEAT"}), 1);  // an error written without a kind is a failure
  EXPECT_EQ(exit_code(Error::input("bad file")), 2);
  static_assert(exit_code(ErrorKind::Unavailable) == 2);
}

TEST(EngineErrorKinds, AMissingFileIsInput) {
  const std::string missing = "/nonexistent/hitl/file";
  auto vehicle = model::load_vehicle_config(missing + ".json");
  ASSERT_FALSE(vehicle);
  EXPECT_EQ(vehicle.error().kind, ErrorKind::Input) << vehicle.error().message;
  auto world = model::load_world_config(missing + ".json");
  ASSERT_FALSE(world);
  EXPECT_EQ(world.error().kind, ErrorKind::Input) << world.error().message;
  auto trajectory = vehicle::Trajectory::load(missing + ".json");
  ASSERT_FALSE(trajectory);
  EXPECT_EQ(trajectory.error().kind, ErrorKind::Input) << trajectory.error().message;
  auto params = vehicle::load_params_file(missing + ".params");
  ASSERT_FALSE(params);
  EXPECT_EQ(params.error().kind, ErrorKind::Input) << params.error().message;
  mavlink::MessageSet set;
  auto dialect = mavlink::load_dialect(missing + ".xml", set);
  ASSERT_FALSE(dialect);
  EXPECT_EQ(dialect.error().kind, ErrorKind::Input) << dialect.error().message;
  EXPECT_EQ(exit_code(dialect.error()), 2);
}

TEST(EngineErrorKinds, AMalformedValueIsInputAndNamesNoOption) {
  auto port = net::parse_port("seventy", "the port");
  ASSERT_FALSE(port);
  EXPECT_EQ(port.error().kind, ErrorKind::Input);
  auto endpoint = net::parse_link_spec("bogus");
  ASSERT_FALSE(endpoint);
  EXPECT_EQ(endpoint.error().kind, ErrorKind::Input);
  EXPECT_EQ(endpoint.error().message,
            "'bogus': expected udp:HOST:PORT, udpin:[HOST:]PORT, tcp:HOST:PORT or tcpin:[HOST:]PORT");  // cli adds --endpoint
}

TEST(EngineErrorKinds, APortInUseIsUnavailable) {
  net::UdpEndpoint::Config c;
  c.bind_address = "127.0.0.1";
  auto held = net::UdpEndpoint::open(c);
  ASSERT_TRUE(held) << held.error().message;
  c.bind_port = held->local_address().port();
  auto again = net::UdpEndpoint::open(c);
  ASSERT_FALSE(again);
  EXPECT_EQ(again.error().kind, ErrorKind::Unavailable) << again.error().message;
  EXPECT_NE(again.error().message.find("in use"), std::string::npos) << again.error().message;
  EXPECT_EQ(exit_code(again.error()), 2);

  auto server = net::TcpServerLink::listen("127.0.0.1", 0, "first");
  ASSERT_TRUE(server) << server.error().message;
  auto second = net::TcpServerLink::listen("127.0.0.1", (*server)->local_address()->port(), "second");
  ASSERT_FALSE(second);
  EXPECT_EQ(second.error().kind, ErrorKind::Unavailable) << second.error().message;
}

TEST(EngineErrorKinds, NobodyListeningIsAFailure) {
  // A closed TCP port: the command ran and the other end did not answer (1), not a usage error.
  auto server = net::TcpServerLink::listen("127.0.0.1", 0, "closed soon");
  ASSERT_TRUE(server) << server.error().message;
  const auto address = *(*server)->local_address();
  server.value().reset();
  net::TcpClientLink::Config c;
  c.server = address;
  c.name = "the board";
  auto client = net::TcpClientLink::open(c);
  ASSERT_FALSE(client);
  EXPECT_EQ(client.error().kind, ErrorKind::Failed) << client.error().message;
  EXPECT_EQ(exit_code(client.error()), 1);
}

}  // namespace
}  // namespace hitl
