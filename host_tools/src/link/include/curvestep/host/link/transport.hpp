// SPDX-License-Identifier: MIT
// Byte transports for the link: one small interface, a termios implementation for
// pseudo-terminals (and any tty given by file descriptor), a libserialport one for real ports,
// pseudo-terminal creation, and serial-port enumeration.
//
// Why two implementations: libserialport enumerates ports with their USB ids and sets baud
// rate and flow control portably, but its sp_open() calls TIOCMGET, which pseudo-terminals
// refuse, so it cannot open a pty. open_port() therefore opens Unix98 pty slaves
// (/dev/pts/N, character major 136..143) with termios directly and everything else with
// libserialport; callers only see Transport.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace curvestep::host::link {

/// The far end closed the line (pty hang-up, USB adapter unplugged) or a read/write failed.
class TransportError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A bidirectional byte stream.
class Transport {
 public:
  virtual ~Transport() = default;
  /// Reads up to out.size() bytes, waiting at most timeout_ms for the first; 0 on timeout.
  /// Throws TransportError if the line is closed or broken.
  virtual std::size_t read(std::span<std::byte> out, int timeout_ms) = 0;
  /// Writes all of `bytes` (blocking). Throws TransportError if the line is closed or broken.
  virtual void write(std::span<const std::byte> bytes) = 0;
  /// The port's name, for messages.
  [[nodiscard]] virtual const std::string& name() const = 0;
};

/// A transport over a file descriptor it owns (termios: ttys and pseudo-terminals).
class FdTransport final : public Transport {
 public:
  /// Takes ownership of `fd`.
  FdTransport(int fd, std::string name);
  ~FdTransport() override;
  FdTransport(const FdTransport&) = delete;
  FdTransport& operator=(const FdTransport&) = delete;
  std::size_t read(std::span<std::byte> out, int timeout_ms) override;
  void write(std::span<const std::byte> bytes) override;
  [[nodiscard]] const std::string& name() const override { return name_; }
  /// The descriptor (still owned by this transport).
  [[nodiscard]] int fd() const noexcept { return fd_; }

 private:
  int fd_ = -1;
  std::string name_;
};

/// Puts a terminal descriptor into raw 8N1 mode at `baud` (0: leave the speed). Throws
/// TransportError naming `name` on failure or for a baud rate termios does not know.
void make_raw(int fd, int baud, const std::string& name);

/// Opens `path` with termios (raw, 8N1, `baud`). Throws TransportError naming the path.
[[nodiscard]] std::unique_ptr<FdTransport> open_terminal(const std::string& path, int baud);

/// Opens a real serial port with libserialport (8N1, no flow control). Throws TransportError
/// with libserialport's message.
[[nodiscard]] std::unique_ptr<Transport> open_serial_port(const std::string& path, int baud);

/// True if `path` is a Unix98 pseudo-terminal slave (libserialport cannot open those).
[[nodiscard]] bool is_pseudo_terminal(const std::string& path);

/// Opens `path` with the right implementation: termios for pseudo-terminals, libserialport otherwise.
[[nodiscard]] std::unique_ptr<Transport> open_port(const std::string& path, int baud);

/// A pseudo-terminal pair created with posix_openpt. The master is this process's end; the
/// slave path is what another program opens. The slave is also kept open here, so the master
/// never reads EIO between clients: a client that goes away is seen as silence, which the link
/// timeout handles.
class PseudoTerminal {
 public:
  /// Creates the pair in raw mode. Throws TransportError.
  PseudoTerminal();
  ~PseudoTerminal();
  PseudoTerminal(const PseudoTerminal&) = delete;
  PseudoTerminal& operator=(const PseudoTerminal&) = delete;
  /// The slave's path (/dev/pts/N).
  [[nodiscard]] const std::string& slave_path() const noexcept { return slave_path_; }
  /// The master descriptor (owned by this object).
  [[nodiscard]] int master_fd() const noexcept { return master_; }
  /// A transport over a duplicate of the master descriptor.
  [[nodiscard]] std::unique_ptr<FdTransport> master_transport() const;

 private:
  int master_ = -1;
  int slave_ = -1;
  std::string slave_path_;
};

/// One serial port as libserialport lists it.
struct PortInfo {
  std::string name;         ///< /dev/ttyUSB0
  std::string description;  ///< adapter description (may be empty)
  std::string transport;    ///< "usb", "bluetooth", "native"
  std::optional<std::uint16_t> usb_vendor_id;   ///< USB vendor id, for USB ports
  std::optional<std::uint16_t> usb_product_id;  ///< USB product id, for USB ports
  std::string usb_manufacturer;  ///< USB manufacturer string (may be empty)
  std::string usb_product;       ///< USB product string (may be empty)
  std::string usb_serial;        ///< USB serial number (may be empty)
};

/// Every serial port libserialport finds. Throws TransportError if enumeration fails.
[[nodiscard]] std::vector<PortInfo> list_ports();

}  // namespace curvestep::host::link
