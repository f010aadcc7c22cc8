#include "engine/doctor/host_probe.h"

#include <arpa/inet.h>
#include <dirent.h>
#include <ifaddrs.h>
#include <net/if.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

#include "engine/net/open_link.h"

namespace hitl::doctor {
namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The processes with a descriptor on one of `inodes` (socket:[INODE]).
std::vector<PortHolder> owners_of(const std::set<uint64_t>& inodes) {
  std::vector<PortHolder> out;
  DIR* proc = ::opendir("/proc");
  if (proc == nullptr) return out;
  while (const dirent* e = ::readdir(proc)) {
    char* end = nullptr;
    const long pid = std::strtol(e->d_name, &end, 10);
    if (end == e->d_name || *end != '\0' || pid <= 0) continue;
    const std::string fd_dir = std::string("/proc/") + e->d_name + "/fd";
    DIR* fds = ::opendir(fd_dir.c_str());
    if (fds == nullptr) continue;  // another user's process
    bool found = false;
    while (const dirent* f = ::readdir(fds)) {
      if (f->d_name[0] == '.') continue;
      char target[64];
      const ssize_t n = ::readlink((fd_dir + "/" + f->d_name).c_str(), target, sizeof target - 1);
      if (n <= 0) continue;
      target[n] = '\0';
      unsigned long long inode = 0;
      if (std::sscanf(target, "socket:[%llu]", &inode) == 1 && inodes.count(inode) != 0) {
        found = true;
        break;
      }
    }
    ::closedir(fds);
    if (!found) continue;
    PortHolder h;
    h.pid = static_cast<int>(pid);
    // "hitl target": the program's name and its first argument that is not an option.
    std::vector<std::string> args;
    std::istringstream cmdline(read_file(std::string("/proc/") + e->d_name + "/cmdline"));
    for (std::string a; std::getline(cmdline, a, '\0');) args.push_back(a);
    if (!args.empty()) h.name = args[0].substr(args[0].rfind('/') == std::string::npos ? 0 : args[0].rfind('/') + 1);
    h.command = h.name;
    for (std::size_t i = 1; i < args.size(); ++i)
      if (!args[i].empty() && args[i][0] != '-') {
        h.command += " " + args[i].substr(0, 60);
        break;
      }
    if (h.name.empty()) {
      h.name = read_file(std::string("/proc/") + e->d_name + "/comm");
      while (!h.name.empty() && h.name.back() == '\n') h.name.pop_back();
    }
    out.push_back(std::move(h));
  }
  ::closedir(proc);
  return out;
}

}  // namespace

std::vector<NetInterface> list_interfaces() {
  std::vector<NetInterface> out;
  ifaddrs* list = nullptr;
  if (::getifaddrs(&list) != 0) return out;
  for (const ifaddrs* i = list; i != nullptr; i = i->ifa_next) {
    if (i->ifa_addr == nullptr || i->ifa_addr->sa_family != AF_INET) continue;
    NetInterface n;
    n.name = i->ifa_name;
    n.address = ntohl(reinterpret_cast<const sockaddr_in*>(i->ifa_addr)->sin_addr.s_addr);
    if (i->ifa_netmask != nullptr) n.netmask = ntohl(reinterpret_cast<const sockaddr_in*>(i->ifa_netmask)->sin_addr.s_addr);
    n.up = (i->ifa_flags & IFF_UP) != 0;
    n.running = (i->ifa_flags & IFF_RUNNING) != 0;
    out.push_back(n);
  }
  ::freeifaddrs(list);
  return out;
}

std::vector<uint64_t> udp_inodes_for_port(const std::string& table, uint16_t port) {
  // "  sl  local_address rem_address   st tx_queue rx_queue tr tm->when retrnsmt   uid  timeout inode"
  // "   0: 0100007F:38A4 00000000:0000 07 00000000:00000000 00:00000000 00000000  1000        0 123456 ..."
  std::vector<uint64_t> out;
  std::istringstream in(table);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::istringstream f(line);
    std::string sl, local, remote, st, queues, timer, retr, uid, timeout;
    uint64_t inode = 0;
    if (!(f >> sl >> local >> remote >> st >> queues >> timer >> retr >> uid >> timeout >> inode)) continue;
    const auto colon = local.rfind(':');
    if (colon == std::string::npos) continue;
    char* end = nullptr;
    const unsigned long p = std::strtoul(local.c_str() + colon + 1, &end, 16);
    if (end == local.c_str() + colon + 1 || *end != '\0') continue;
    if (p == port && inode != 0) out.push_back(inode);
  }
  return out;
}

PortProbe probe_udp_port(uint16_t port, const std::string& role) {
  PortProbe p;
  p.port = port;
  p.role = role;
  const auto in_use = net::udp_port_in_use(port);
  if (!in_use) {
    p.error = in_use.error().message;
    return p;
  }
  p.taken = *in_use;
  if (!p.taken) return p;
  std::set<uint64_t> inodes;
  for (const char* table : {"/proc/net/udp", "/proc/net/udp6"})
    for (uint64_t inode : udp_inodes_for_port(read_file(table), port)) inodes.insert(inode);
  if (!inodes.empty()) p.holders = owners_of(inodes);
  return p;
}

}  // namespace hitl::doctor
