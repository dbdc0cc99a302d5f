// SPDX-License-Identifier: MIT
// Parameter substitution in DEBUG and PRINT comments.
#include "message_text.hpp"

#include <cstdio>
#include <optional>

#include <curvestep/host/gcode/program_block.hpp>

namespace curvestep::host::gcode::detail {
namespace {

std::string format_value(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6f", value);
  return buffer;
}

}  // namespace

std::string substitute_parameters(std::string_view text, const ParameterSource& parameters) {
  std::string out;
  std::size_t i = 0;
  while (i < text.size()) {
    if (text[i] != '#') {
      out += text[i++];
      continue;
    }
    std::optional<double> value;
    std::size_t stop = i + 1;
    if (stop < text.size() && text[stop] == '<') {
      const std::size_t close = text.find('>', stop);
      if (close != std::string_view::npos) {
        std::string name;
        for (std::size_t k = stop + 1; k < close; ++k) {
          const char c = text[k];
          if (c == ' ' || c == '\t') continue;
          name += (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
        }
        value = parameters.named(name);
        stop = close + 1;
      }
    } else {
      long number = 0;
      while (stop < text.size() && text[stop] >= '0' && text[stop] <= '9' && number <= ParameterStore::max_numbered) {
        number = number * 10 + (text[stop] - '0');
        ++stop;
      }
      if (stop > i + 1 && number >= 1 && number <= ParameterStore::max_numbered) value = parameters.numbered(static_cast<int>(number));
    }
    if (value) {
      out += format_value(*value);
    } else {
      out += text.substr(i, stop - i);
    }
    i = stop;
  }
  return out;
}

}  // namespace curvestep::host::gcode::detail
