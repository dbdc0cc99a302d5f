// SPDX-License-Identifier: MIT
// LoadError formatting.
#include <curvestep/host/load_error.hpp>

#include <utility>

#include <curvestep/host/printable.hpp>

namespace curvestep::host {

std::string format_load_error(const SourceLocation& location, const std::string& message) {
  std::string text = location.file.empty() ? std::string("<input>") : location.file;
  if (location.line > 0) {
    text += ":" + std::to_string(location.line);
    if (location.column > 0) text += ":" + std::to_string(location.column);
  }
  text += ": ";
  if (location.segment) {
    text += "segment " + std::to_string(*location.segment);
    if (!location.segment_type.empty()) text += " (" + location.segment_type + ")";
    text += ": ";
  }
  if (!location.field.empty()) text += location.field + ": ";
  // One line, safe for a terminal: input quoted in the message (ids, words, file names) is escaped.
  return printable(text + message);
}

LoadError::LoadError(SourceLocation location, std::string message, Error code)
    : std::runtime_error(format_load_error(location, message)),
      location_(std::move(location)),
      message_(std::move(message)),
      code_(code) {}

}  // namespace curvestep::host
