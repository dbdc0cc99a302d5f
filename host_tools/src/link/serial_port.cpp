// SPDX-License-Identifier: MIT
// libserialport transport for real serial ports, and port enumeration.
#include <curvestep/host/link/transport.hpp>

#include <libserialport.h>

namespace curvestep::host::link {
namespace {

std::string last_error(const std::string& name, const char* what) {
  char* message = sp_last_error_message();
  std::string text = name + ": " + what + ": " + (message != nullptr ? message : "unknown error");
  sp_free_error_message(message);
  return text;
}

class SerialPortTransport final : public Transport {
 public:
  SerialPortTransport(const std::string& path, int baud) : name_(path) {
    if (sp_get_port_by_name(path.c_str(), &port_) != SP_OK) throw TransportError(last_error(path, "no such serial port"));
    if (sp_open(port_, SP_MODE_READ_WRITE) != SP_OK) {
      const std::string text = last_error(path, "cannot open");
      sp_free_port(port_);
      throw TransportError(text);
    }
    if (sp_set_baudrate(port_, baud) != SP_OK || sp_set_bits(port_, 8) != SP_OK ||
        sp_set_parity(port_, SP_PARITY_NONE) != SP_OK || sp_set_stopbits(port_, 1) != SP_OK ||
        sp_set_flowcontrol(port_, SP_FLOWCONTROL_NONE) != SP_OK) {
      const std::string text = last_error(path, "cannot configure");
      sp_close(port_);
      sp_free_port(port_);
      throw TransportError(text);
    }
  }
  ~SerialPortTransport() override {
    sp_close(port_);
    sp_free_port(port_);
  }
  SerialPortTransport(const SerialPortTransport&) = delete;
  SerialPortTransport& operator=(const SerialPortTransport&) = delete;

  std::size_t read(std::span<std::byte> out, int timeout_ms) override {
    const sp_return n = sp_blocking_read_next(port_, out.data(), out.size(), static_cast<unsigned>(timeout_ms < 0 ? 0 : timeout_ms));
    if (n < 0) throw TransportError(last_error(name_, "read"));
    return static_cast<std::size_t>(n);
  }
  void write(std::span<const std::byte> bytes) override {
    const sp_return n = sp_blocking_write(port_, bytes.data(), bytes.size(), 2000);
    if (n < 0) throw TransportError(last_error(name_, "write"));
    if (static_cast<std::size_t>(n) != bytes.size()) throw TransportError(name_ + ": write timed out");
  }
  [[nodiscard]] const std::string& name() const override { return name_; }

 private:
  sp_port* port_ = nullptr;
  std::string name_;
};

std::string text_or_empty(const char* s) { return s != nullptr ? std::string(s) : std::string(); }

}  // namespace

std::unique_ptr<Transport> open_serial_port(const std::string& path, int baud) {
  return std::make_unique<SerialPortTransport>(path, baud);
}

std::vector<PortInfo> list_ports() {
  sp_port** ports = nullptr;
  if (sp_list_ports(&ports) != SP_OK) throw TransportError(last_error("serial ports", "cannot list"));
  std::vector<PortInfo> result;
  for (std::size_t i = 0; ports[i] != nullptr; ++i) {
    sp_port* port = ports[i];
    PortInfo info;
    info.name = text_or_empty(sp_get_port_name(port));
    info.description = text_or_empty(sp_get_port_description(port));
    switch (sp_get_port_transport(port)) {
      case SP_TRANSPORT_USB: {
        info.transport = "usb";
        int vendor = 0;
        int product = 0;
        if (sp_get_port_usb_vid_pid(port, &vendor, &product) == SP_OK) {
          info.usb_vendor_id = static_cast<std::uint16_t>(vendor);
          info.usb_product_id = static_cast<std::uint16_t>(product);
        }
        info.usb_manufacturer = text_or_empty(sp_get_port_usb_manufacturer(port));
        info.usb_product = text_or_empty(sp_get_port_usb_product(port));
        info.usb_serial = text_or_empty(sp_get_port_usb_serial(port));
        break;
      }
      case SP_TRANSPORT_BLUETOOTH: info.transport = "bluetooth"; break;
      default: info.transport = "native"; break;
    }
    result.push_back(std::move(info));
  }
  sp_free_port_list(ports);
  return result;
}

}  // namespace curvestep::host::link
