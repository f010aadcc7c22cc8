#include "target/vio-server/raw_fifo_pipe.h"

#include <fcntl.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace hitl::vio {

RawFifoPipe::RawFifoPipe(std::string path, int fd, int size_bytes) : path_(std::move(path)), fd_(fd), size_bytes_(size_bytes) {}

Expected<std::unique_ptr<RawFifoPipe>> RawFifoPipe::create(const std::string& base_dir, const std::string& name, int size_bytes) {
  if (base_dir.empty() || base_dir[0] != '/') return Error{"the MPA base directory must be an absolute path, not \"" + base_dir + "\""};
  std::string path = base_dir;
  if (path.back() != '/') path += '/';
  if (::mkdir(path.c_str(), 0775) != 0 && errno != EEXIST) return Error{"cannot create " + path + ": " + std::strerror(errno)};
  path += name;
  struct stat st{};
  if (::lstat(path.c_str(), &st) == 0 && !S_ISFIFO(st.st_mode)) {
    return Error{path + " exists and is not a FIFO (an MPA pipe directory? stop the server that made it)"};
  }
  if (::mkfifo(path.c_str(), 0666) != 0 && errno != EEXIST) return Error{"cannot create the FIFO " + path + ": " + std::strerror(errno)};
  // Read-write, as ModalAI's bridge does: never ENXIO or EPIPE, whether or not vision-hub reads.
  const int fd = ::open(path.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return Error{"cannot open the FIFO " + path + ": " + std::strerror(errno)};
  std::unique_ptr<RawFifoPipe> pipe(new RawFifoPipe(path, fd, size_bytes));
  int size = ::fcntl(fd, F_SETPIPE_SZ, size_bytes);
  if (size < size_bytes) {
    size = ::fcntl(fd, F_GETPIPE_SZ);
    pipe->events_.push_back("pipe size of " + path + " is " + std::to_string(size) + " bytes, not " + std::to_string(size_bytes));
  }
  pipe->size_bytes_ = size;
  return pipe;
}

RawFifoPipe::~RawFifoPipe() {
  ::close(fd_);
  ::unlink(path_.c_str());
}

std::vector<std::string> RawFifoPipe::take_events() {
  std::vector<std::string> out;
  out.swap(events_);
  return out;
}

void RawFifoPipe::write(std::span<const uint8_t> record) {
  int queued = 0;
  if (::ioctl(fd_, FIONREAD, &queued) == 0 && size_bytes_ - queued < static_cast<int>(record.size())) {
    ++counters_.records_dropped;  // nobody is reading, or too slowly: keep records whole
    return;
  }
  if (::write(fd_, record.data(), record.size()) == static_cast<ssize_t>(record.size())) {
    ++counters_.records_written;
  } else {
    ++counters_.records_dropped;
  }
}

}  // namespace hitl::vio
