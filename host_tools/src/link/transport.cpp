// SPDX-License-Identifier: MIT
// termios transports and pseudo-terminals (libserialport cannot open ptys: see transport.hpp).
#include <curvestep/host/link/transport.hpp>

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <termios.h>
#include <unistd.h>

namespace curvestep::host::link {
namespace {

[[noreturn]] void throw_errno(const std::string& what, const std::string& name) {
  throw TransportError(name + ": " + what + ": " + std::strerror(errno));
}

speed_t to_speed(int baud, const std::string& name) {
  switch (baud) {
    case 9600: return B9600;
    case 19200: return B19200;
    case 38400: return B38400;
    case 57600: return B57600;
    case 115200: return B115200;
    case 230400: return B230400;
    case 460800: return B460800;
    case 921600: return B921600;
    case 1000000: return B1000000;
    case 2000000: return B2000000;
    default: throw TransportError(name + ": unsupported baud rate " + std::to_string(baud));
  }
}

}  // namespace

FdTransport::FdTransport(int fd, std::string name) : fd_(fd), name_(std::move(name)) {}

FdTransport::~FdTransport() {
  if (fd_ >= 0) ::close(fd_);
}

std::size_t FdTransport::read(std::span<std::byte> out, int timeout_ms) {
  pollfd p{fd_, POLLIN, 0};
  const int ready = ::poll(&p, 1, timeout_ms);
  if (ready < 0) {
    if (errno == EINTR) return 0;
    throw_errno("poll", name_);
  }
  if (ready == 0) return 0;
  if ((p.revents & POLLIN) == 0 && (p.revents & (POLLHUP | POLLERR | POLLNVAL)) != 0) {
    throw TransportError(name_ + ": the line was closed by the other end");
  }
  const ssize_t n = ::read(fd_, out.data(), out.size());
  if (n < 0) {
    if (errno == EAGAIN || errno == EINTR) return 0;
    if (errno == EIO) throw TransportError(name_ + ": the line was closed by the other end");
    throw_errno("read", name_);
  }
  if (n == 0) throw TransportError(name_ + ": the line was closed by the other end");
  return static_cast<std::size_t>(n);
}

void FdTransport::write(std::span<const std::byte> bytes) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      if (errno == EAGAIN) {
        pollfd p{fd_, POLLOUT, 0};
        if (::poll(&p, 1, 1000) < 0 && errno != EINTR) throw_errno("poll", name_);
        if ((p.revents & (POLLHUP | POLLERR)) != 0) throw TransportError(name_ + ": the line was closed by the other end");
        continue;
      }
      if (errno == EIO) throw TransportError(name_ + ": the line was closed by the other end");
      throw_errno("write", name_);
    }
    done += static_cast<std::size_t>(n);
  }
}

void make_raw(int fd, int baud, const std::string& name) {
  termios t{};
  if (::tcgetattr(fd, &t) != 0) throw_errno("tcgetattr (not a terminal?)", name);
  ::cfmakeraw(&t);
  t.c_cflag |= CLOCAL | CREAD;
  t.c_cflag &= ~static_cast<tcflag_t>(CSTOPB | CRTSCTS);
  t.c_cc[VMIN] = 0;
  t.c_cc[VTIME] = 0;
  if (baud > 0) {
    const speed_t speed = to_speed(baud, name);
    ::cfsetispeed(&t, speed);
    ::cfsetospeed(&t, speed);
  }
  if (::tcsetattr(fd, TCSANOW, &t) != 0) throw_errno("tcsetattr", name);
}

std::unique_ptr<FdTransport> open_terminal(const std::string& path, int baud) {
  const int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw_errno("cannot open", path);
  auto transport = std::make_unique<FdTransport>(fd, path);
  make_raw(fd, baud, path);
  return transport;
}

bool is_pseudo_terminal(const std::string& path) {
  struct stat s{};
  if (::stat(path.c_str(), &s) != 0 || !S_ISCHR(s.st_mode)) return false;
  const unsigned major_number = major(s.st_rdev);
  return major_number >= 136 && major_number <= 143;  // Unix98 pty slaves
}

std::unique_ptr<Transport> open_port(const std::string& path, int baud) {
  if (is_pseudo_terminal(path)) return open_terminal(path, baud);
  return open_serial_port(path, baud);
}

PseudoTerminal::PseudoTerminal() {
  master_ = ::posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (master_ < 0) throw_errno("posix_openpt", "pseudo-terminal");
  if (::grantpt(master_) != 0 || ::unlockpt(master_) != 0) {
    ::close(master_);
    throw_errno("grantpt/unlockpt", "pseudo-terminal");
  }
  char buffer[128] = {};
  if (::ptsname_r(master_, buffer, sizeof buffer) != 0) {
    ::close(master_);
    throw_errno("ptsname", "pseudo-terminal");
  }
  slave_path_ = buffer;
  slave_ = ::open(buffer, O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (slave_ < 0) {
    ::close(master_);
    throw_errno("cannot open", slave_path_);
  }
  make_raw(slave_, 0, slave_path_);
  const int flags = ::fcntl(master_, F_GETFL);
  ::fcntl(master_, F_SETFL, flags | O_NONBLOCK);
}

PseudoTerminal::~PseudoTerminal() {
  if (slave_ >= 0) ::close(slave_);
  if (master_ >= 0) ::close(master_);
}

std::unique_ptr<FdTransport> PseudoTerminal::master_transport() const {
  const int fd = ::fcntl(master_, F_DUPFD_CLOEXEC, 0);
  if (fd < 0) throw_errno("dup", slave_path_);
  return std::make_unique<FdTransport>(fd, slave_path_ + " (master)");
}

}  // namespace curvestep::host::link
