// SPDX-License-Identifier: MIT
#include "gpiod_request.hpp"

#include <cerrno>
#include <cstring>

#include <curvestep/boards/host/gpio_output.hpp>

namespace curvestep::boards::host::detail {
namespace {

constexpr const char* consumer = "curvestep";

}  // namespace

gpiod_chip* open_chip(const std::string& chip) {
  if (chip.empty()) throw GpioError("GPIO: no chip given (machine file: \"gpio\": {\"chip\": ...})");
  gpiod_chip* opened = gpiod_chip_open_lookup(chip.c_str());
  if (opened == nullptr) {
    throw GpioError("GPIO chip \"" + chip + "\" not found: " + std::strerror(errno) +
                    " (list chips with gpiodetect; this machine may have none)");
  }
  return opened;
}

gpiod_line* request_output_line(gpiod_chip* chip, const std::string& chip_name, const std::string& name, const std::string& role) {
  gpiod_line* line = gpiod_chip_find_line(chip, name.c_str());
  if (line == nullptr) throw GpioError("GPIO line \"" + name + "\" (" + role + ") not found on chip \"" + chip_name + "\"");
  if (gpiod_line_request_output(line, consumer, 0) != 0) {
    throw GpioError("GPIO line \"" + name + "\" (" + role + ") on chip \"" + chip_name +
                    "\" cannot be requested as an output: " + std::strerror(errno));
  }
  return line;
}

}  // namespace curvestep::boards::host::detail
