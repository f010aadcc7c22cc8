#include "engine/px4/px4_instance.h"

#include <fcntl.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstring>

namespace hitl::px4 {
namespace {

/// True when a process holds a write lock on `path` (PX4's is_server_running() asks the same way).
bool locked(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;  // no file: no PX4 ran as this instance since boot
  struct flock lock;
  std::memset(&lock, 0, sizeof lock);
  lock.l_type = F_WRLCK;
  lock.l_whence = SEEK_SET;
  const bool held = ::fcntl(fd, F_GETLK, &lock) == 0 && lock.l_type != F_UNLCK;
  ::close(fd);
  return held;
}

/// True when UDP `port` can be bound on every address now (PX4 binds its MAVLink ports on INADDR_ANY).
bool udp_port_free(uint16_t port) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return true;  // cannot tell; PX4 will say
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  a.sin_addr.s_addr = htonl(INADDR_ANY);
  const bool free = ::bind(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a) == 0;
  ::close(fd);
  return free;
}

}  // namespace

std::string px4_instance_busy(const Px4Instance& i) {
  if (locked(i.lock_file()))
    return "a PX4 runs as instance " + std::to_string(i.index) + " (" + i.lock_file() + " is locked)";
  if (!udp_port_free(i.gcs_udp_port()))
    return "UDP " + std::to_string(i.gcs_udp_port()) + " (its GCS MAVLink port) is in use";
  if (!udp_port_free(i.offboard_udp_port()))
    return "UDP " + std::to_string(i.offboard_udp_port()) + " (its offboard MAVLink port) is in use";
  return "";
}

}  // namespace hitl::px4
