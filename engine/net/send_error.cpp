#include "engine/net/send_error.h"

#include <cerrno>
#include <cstring>

namespace hitl::net {
namespace {

const char* errno_name(int error) {
  switch (error) {
    case ENETUNREACH: return "ENETUNREACH";
    case EHOSTUNREACH: return "EHOSTUNREACH";
    case EINVAL: return "EINVAL";
    case EACCES: return "EACCES";
    case EPERM: return "EPERM";
    case ENOBUFS: return "ENOBUFS";
    case EAGAIN: return "EAGAIN";
    case ECONNREFUSED: return "ECONNREFUSED";
    case EMSGSIZE: return "EMSGSIZE";
    case EADDRNOTAVAIL: return "EADDRNOTAVAIL";
    case ENETDOWN: return "ENETDOWN";
    default: return nullptr;
  }
}

/// 192.168.101.100/24 for a board at 192.168.101.2: the host's address on the board's subnet.
std::string host_address_for(const std::string& board) {
  const auto dot = board.rfind('.');
  if (dot == std::string::npos || board.find(':') != std::string::npos) return "an address on " + board + "'s subnet";
  return board.substr(0, dot) + ".100/24";
}

}  // namespace

std::string send_error_hint(int error, const SocketAddress& local, const SocketAddress& to) {
  const std::string board = to.host();
  switch (error) {
    case ENETUNREACH:
    case EHOSTUNREACH:
    case ENETDOWN:
      return "this host has no route to " + board +
             ": connect the board's USB-C cable (its USB-Ethernet appears as usb0 or enx...) and give this host an address "
             "there (sudo ip addr add " + host_address_for(board) + " dev usb0), or use --adb; hitl doctor -i " + board +
             " checks the route";
    case EINVAL:
    case EADDRNOTAVAIL:
      if (local.is_loopback() && !to.is_loopback())
        return "the socket is bound to " + local.host() + " (--bind), which cannot reach " + board +
               ": bind to 0.0.0.0 or to this host's address on the board's network";
      return {};
    case EACCES:
    case EPERM: return "sending to " + board + " is not permitted (a broadcast address, or a firewall rule)";
    case ENOBUFS:
    case EAGAIN: return "the send buffer is full: the link carries less than the stream";
    case ECONNREFUSED: return "nothing listens on " + to.to_string();
    default: return {};
  }
}

std::string describe_send_error(int error, const SocketAddress& local, const SocketAddress& to) {
  std::string text = "cannot send to " + to.to_string() + ": " + std::strerror(error);
  if (const char* name = errno_name(error)) text += std::string(" (") + name + ")";
  if (const auto hint = send_error_hint(error, local, to); !hint.empty()) text += "; " + hint;
  return text;
}

}  // namespace hitl::net
