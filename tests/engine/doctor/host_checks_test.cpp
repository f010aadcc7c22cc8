// The doctor's host checks (engine/doctor/host_checks, host_probe) on fixed inputs: the route to the
// board, adb devices, the ports free or held by whom, /proc/net/udp read for a port's holders.
#include <gtest/gtest.h>

#include <vector>

#include "engine/doctor/host_checks.h"
#include "engine/doctor/host_probe.h"
#include "tests/engine/doctor/check_fixtures.h"

namespace hitl::doctor {
namespace {

using namespace fixtures;

NetInterface iface(const char* name, const char* ip, int prefix, bool up, bool running = true) {
  NetInterface i;
  i.name = name;
  i.address = *parse_ipv4(ip);
  i.netmask = prefix == 0 ? 0 : 0xFFFFFFFFu << (32 - prefix);
  i.up = up;
  i.running = running;
  return i;
}

TEST(DoctorHost, RouteToTheBoard) {
  const auto lo = iface("lo", "127.0.0.1", 8, true);
  const auto eth = iface("eth0", "10.0.0.5", 24, true);
  EXPECT_EQ(route_check("127.0.0.1", {lo}).result, Verdict::Skip);
  auto ok = route_check("192.168.101.2", {lo, eth, iface("usb0", "192.168.101.100", 24, true)});
  EXPECT_EQ(ok.result, Verdict::Pass);
  EXPECT_TRUE(has(ok.saw, "usb0 192.168.101.100/24 up")) << ok.saw;
  auto down = route_check("192.168.101.2", {iface("usb0", "192.168.101.100", 24, false, false)});
  EXPECT_EQ(down.result, Verdict::Fail);
  EXPECT_TRUE(has(down.fix, "ip link set usb0 up")) << down.fix;
  auto none = route_check("192.168.101.2", {lo, eth});
  EXPECT_EQ(none.result, Verdict::Fail);
  EXPECT_TRUE(has(none.saw, "192.168.101.0/24")) << none.saw;
  EXPECT_TRUE(has(none.saw, "eth0 10.0.0.5/24 up")) << none.saw;
  EXPECT_TRUE(has(none.fix, "sudo ip addr add 192.168.101.100/24")) << none.fix;
  EXPECT_EQ(route_check("board.local", {eth}).result, Verdict::Fail);
}

TEST(DoctorHost, AdbDevices) {
  EXPECT_EQ(adb_check(false, "", Error{"x"}).result, Verdict::Skip);
  auto missing = adb_check(true, "", Error{"adb not found on PATH: install the Debian package adb"});
  EXPECT_EQ(missing.result, Verdict::Fail);
  EXPECT_TRUE(has(missing.fix, "apt-get install adb"));
  net::AdbDevices none{"/usr/bin/adb", {}};
  EXPECT_EQ(adb_check(true, "", none).result, Verdict::Fail);
  net::AdbDevices one{"/usr/bin/adb", {{"a1b2", "device"}}};
  EXPECT_EQ(adb_check(true, "", one).result, Verdict::Pass);
  EXPECT_EQ(adb_check(true, "zzz", one).result, Verdict::Fail);
  net::AdbDevices locked{"/usr/bin/adb", {{"a1b2", "unauthorized"}}};
  auto u = adb_check(true, "", locked);
  EXPECT_EQ(u.result, Verdict::Fail);
  EXPECT_TRUE(has(u.saw, "unauthorized")) << u.saw;
  net::AdbDevices two{"/usr/bin/adb", {{"a", "device"}, {"b", "device"}}};
  EXPECT_EQ(adb_check(true, "", two).result, Verdict::Fail);
  EXPECT_EQ(adb_check(true, "b", two).result, Verdict::Pass);
}

PortProbe probe(uint16_t port, bool taken, std::vector<PortHolder> holders = {}) {
  PortProbe p;
  p.port = port;
  p.role = port == 14560 ? "HIL" : "VIO";
  p.taken = taken;
  p.holders = std::move(holders);
  return p;
}

TEST(DoctorHost, PortsFreeForARemoteBoardHeldByTheStandInForALocalOne) {
  const PortHolder hitl{4242, "hitl target --hil-port 14560", "hitl"};
  const PortHolder python{777, "python3 -c import socket ...", "python3"};
  EXPECT_EQ(ports_check({probe(14560, false), probe(14570, false)}, false).result, Verdict::Pass);
  auto listener = ports_check({probe(14560, false), probe(14570, true, {python})}, false);
  EXPECT_EQ(listener.result, Verdict::Fail);
  EXPECT_TRUE(has(listener.saw, "VIO UDP 14570 is taken by 'python3 -c import socket ...' (pid 777)")) << listener.saw;
  EXPECT_TRUE(has(listener.fix, "kill 777")) << listener.fix;
  EXPECT_EQ(ports_check({probe(14560, true, {hitl}), probe(14570, true, {hitl})}, true).result, Verdict::Pass);
  EXPECT_EQ(ports_check({probe(14560, true, {hitl}), probe(14570, true, {python})}, true).result, Verdict::Fail);
  EXPECT_EQ(ports_check({probe(14560, true, {hitl}), probe(14570, false)}, true).result, Verdict::Warn);
  EXPECT_EQ(ports_check({probe(14560, true)}, false).result, Verdict::Fail);  // someone this user cannot see
  EXPECT_EQ(ports_check({probe(14560, true)}, true).result, Verdict::Warn);
}

TEST(DoctorHost, ProcNetUdpInodes) {
  const std::string table =
      "  sl  local_address rem_address   st tx_queue rx_queue tr tm->when retrnsmt   uid  timeout inode ref pointer drops\n"
      "  311: 0100007F:38E0 00000000:0000 07 00000000:00000000 00:00000000 00000000  1000        0 987654 2 0 0\n"
      "  312: 00000000:38EA 00000000:0000 07 00000000:00000000 00:00000000 00000000  1000        0 123 2 0 0\n"
      "garbage line\n";
  EXPECT_EQ(udp_inodes_for_port(table, 14560), std::vector<uint64_t>{987654});  // 0x38E0
  EXPECT_EQ(udp_inodes_for_port(table, 14570), std::vector<uint64_t>{123});     // 0x38EA
  EXPECT_TRUE(udp_inodes_for_port(table, 14558).empty());
  EXPECT_TRUE(udp_inodes_for_port("", 14560).empty());
  EXPECT_TRUE(is_loopback_host("127.0.0.1"));
  EXPECT_TRUE(is_loopback_host("localhost"));
  EXPECT_FALSE(is_loopback_host("192.168.101.2"));
}

}  // namespace
}  // namespace hitl::doctor
