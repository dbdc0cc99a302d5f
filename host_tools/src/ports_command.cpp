// SPDX-License-Identifier: MIT
// `curvestep ports`: lists serial ports with description and USB vendor/product ids (libserialport).
#include <cstdio>
#include <iostream>
#include <memory>

#include <curvestep/host/link/transport.hpp>

#include "command_registry.hpp"

namespace curvestep::host {
namespace {

std::string hex4(std::uint16_t value) {
  char text[8];
  std::snprintf(text, sizeof text, "%04x", static_cast<unsigned>(value));
  return text;
}

int run_ports() {
  const auto ports = link::list_ports();
  if (ports.empty()) {
    std::cout << "no serial ports found (pseudo-terminals are not listed: use the path `curvestep device` prints)\n";
    return 0;
  }
  for (const auto& p : ports) {
    std::cout << p.name << "  " << (p.description.empty() ? "-" : p.description) << "  " << p.transport;
    if (p.usb_vendor_id && p.usb_product_id) std::cout << "  " << hex4(*p.usb_vendor_id) << ":" << hex4(*p.usb_product_id);
    if (!p.usb_manufacturer.empty()) std::cout << "  " << p.usb_manufacturer;
    if (!p.usb_product.empty()) std::cout << " " << p.usb_product;
    if (!p.usb_serial.empty()) std::cout << "  serial " << p.usb_serial;
    std::cout << "\n";
  }
  return 0;
}

void add_ports_command(CLI::App& app) {
  auto* ports = app.add_subcommand("ports", "List serial ports with description and USB vendor:product ids");
  ports->callback([] { run_ports(); });
}

const RegisterCommand registered{55, add_ports_command};

}  // namespace
}  // namespace curvestep::host
