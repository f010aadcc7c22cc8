#include "engine/doctor/host_checks.h"

#include <arpa/inet.h>


#include "engine/doctor/check_catalog.h"

namespace hitl::doctor {
namespace {

int prefix_length(uint32_t netmask) {
  int n = 0;
  while (n < 32 && (netmask & (0x80000000u >> n)) != 0) ++n;
  return n;
}

std::string describe(const NetInterface& i) {
  return i.name + " " + format_ipv4(i.address) + "/" + std::to_string(prefix_length(i.netmask)) +
         (i.up ? (i.running ? " up" : " up, no carrier") : " down");
}

std::string holders_text(const std::vector<PortHolder>& holders) {
  std::string out;
  for (const auto& h : holders) {
    if (!out.empty()) out += ", ";
    out += "'" + (h.command.empty() ? h.name : h.command) + "' (pid " + std::to_string(h.pid) + ")";
  }
  return out;
}

}  // namespace

std::optional<uint32_t> parse_ipv4(const std::string& text) {
  in_addr a{};
  if (::inet_pton(AF_INET, text.c_str(), &a) != 1) return std::nullopt;
  return ntohl(a.s_addr);
}

std::string format_ipv4(uint32_t address) {
  return std::to_string(address >> 24) + "." + std::to_string((address >> 16) & 0xFF) + "." +
         std::to_string((address >> 8) & 0xFF) + "." + std::to_string(address & 0xFF);
}

bool is_loopback_host(const std::string& host) {
  if (host == "localhost") return true;
  const auto a = parse_ipv4(host);
  return a && (*a >> 24) == 127;
}

CheckResult route_check(const std::string& board_ip, const std::vector<NetInterface>& interfaces) {
  if (is_loopback_host(board_ip))
    return make_result(check::kRoute, Verdict::Skip,
                       "the board is " + board_ip + " on this host (hitl target, or a tunnel over adb): no USB-Ethernet route needed");
  const auto ip = parse_ipv4(board_ip);
  if (!ip)
    return make_result(check::kRoute, Verdict::Fail, "-i " + board_ip + " is not an IPv4 address",
                       "give the board's USB-Ethernet address: hitl doctor -i 192.168.101.2 (find it with: adb shell ip addr)");
  const std::string subnet24 = format_ipv4(*ip & 0xFFFFFF00u) + "/24";
  const std::string add_address =
      "sudo ip addr add " + format_ipv4((*ip & 0xFFFFFF00u) | 100u) + "/24 dev usb0 && sudo ip link set usb0 up";
  std::vector<const NetInterface*> on_subnet;
  for (const auto& i : interfaces)
    if (i.netmask != 0 && (i.address & i.netmask) == (*ip & i.netmask) && (i.address >> 24) != 127) on_subnet.push_back(&i);
  for (const auto* i : on_subnet)
    if (i->up && i->running)
      return make_result(check::kRoute, Verdict::Pass, board_ip + " is on " + describe(*i));
  if (!on_subnet.empty())
    return make_result(check::kRoute, Verdict::Fail, board_ip + " is on " + describe(*on_subnet.front()) + ": the link is not up",
                       "plug the board's USB-C cable in, then: sudo ip link set " + on_subnet.front()->name + " up");
  std::string seen;
  for (const auto& i : interfaces) {
    if ((i.address >> 24) == 127) continue;
    seen += (seen.empty() ? "" : "; ") + describe(i);
  }
  return make_result(check::kRoute, Verdict::Fail,
                     "no interface has an address in " + board_ip + "'s subnet (" + subnet24 + "); interfaces: " +
                         (seen.empty() ? "none but loopback" : seen),
                     "connect the board's USB-C cable (its USB-Ethernet appears as usb0 or enx...), then give this host an "
                     "address there: " + add_address);
}

CheckResult adb_check(bool wanted, const std::string& serial, const Expected<net::AdbDevices>& listing) {
  if (!wanted) return make_result(check::kAdb, Verdict::Skip, "--adb not given: the board is reached over IP");
  if (!listing) return make_result(check::kAdb, Verdict::Fail, listing.error().message, "sudo apt-get install adb");
  auto chosen = net::choose_adb_device(listing.value().devices, serial);
  if (!chosen) {
    const char* fix = listing.value().devices.empty() ? "plug the board's USB-C cable in, wait for it to boot, then: adb devices"
                                               : "adb devices; then hitl doctor --adb-serial SERIAL with the board's serial";
    return make_result(check::kAdb, Verdict::Fail, chosen.error().message, fix);
  }
  return make_result(check::kAdb, Verdict::Pass, chosen.value() + " ready (" + std::to_string(listing.value().devices.size()) +
                                                     " device(s) listed by " + listing.value().adb_path + ")");
}

bool is_board_stand_in(const PortHolder& holder) {
  for (const char* n : {"hitl", "hitl-adb-relay", "adb", "px4", "voxl-hitl-vio-server"})
    if (holder.name == n) return true;
  return false;
}

CheckResult ports_check(const std::vector<PortProbe>& probes, bool board_on_this_host) {
  Verdict verdict = Verdict::Pass;
  std::string saw, fix;
  auto add = [&](Verdict v, const std::string& text, const std::string& f) {
    verdict = worse(verdict, v);
    saw += (saw.empty() ? "" : "; ") + text;
    if (!f.empty() && fix.empty()) fix = f;
  };
  for (const auto& p : probes) {
    const std::string what = p.role + " UDP " + std::to_string(p.port);
    if (!p.error.empty()) {
      add(Verdict::Warn, what + ": " + p.error, "");
      continue;
    }
    if (!p.taken) {
      if (board_on_this_host)
        add(Verdict::Warn, what + " is free: nothing on this host receives what is sent there",
            "start the board's stand-in (hitl target, or the adb tunnel: hitl bridge --adb)");
      else
        add(Verdict::Pass, what + " free", "");
      continue;
    }
    if (p.holders.empty()) {
      add(board_on_this_host ? Verdict::Warn : Verdict::Fail, what + " is taken by a process this user cannot see",
          "sudo ss -ulpn 'sport = :" + std::to_string(p.port) + "' names it; stop it");
      continue;
    }
    bool stand_in = true;
    for (const auto& h : p.holders) stand_in = stand_in && is_board_stand_in(h);
    if (board_on_this_host && stand_in) {
      add(Verdict::Pass, what + " held by the board's stand-in " + holders_text(p.holders), "");
    } else {
      add(Verdict::Fail,
          what + " is taken by " + holders_text(p.holders) +
              (board_on_this_host ? ", not by the board's stand-in" : ": the board is remote, so it receives what was meant for the board"),
          "stop it: kill " + std::to_string(p.holders.front().pid) + " (a listener left from the spec's Phase 1?)");
    }
  }
  return make_result(check::kPorts, verdict, saw, fix);
}

}  // namespace hitl::doctor
