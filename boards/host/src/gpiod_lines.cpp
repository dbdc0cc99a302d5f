// SPDX-License-Identifier: MIT
#include <curvestep/boards/host/gpiod_lines.hpp>

#include <gpiod.h>

#include "gpiod_request.hpp"

namespace curvestep::boards::host {

GpiodLineSet::GpiodLineSet(const std::string& chip, const std::vector<std::pair<std::string, std::string>>& lines) {
  chip_ = detail::open_chip(chip);
  try {
    for (const auto& [name, role] : lines) {
      lines_.push_back(name.empty() ? nullptr : detail::request_output_line(chip_, chip, name, role));
    }
  } catch (...) {
    gpiod_chip_close(chip_);  // also releases the lines requested so far
    throw;
  }
}

GpiodLineSet::~GpiodLineSet() {
  for (std::size_t k = 0; k < lines_.size(); ++k) set(k, false);
  gpiod_chip_close(chip_);
}

void GpiodLineSet::set(std::size_t index, bool high) noexcept {
  if (index >= lines_.size() || lines_[index] == nullptr) return;
  if (gpiod_line_set_value(lines_[index], high ? 1 : 0) != 0) write_errors_.fetch_add(1, std::memory_order_relaxed);
}

}  // namespace curvestep::boards::host
