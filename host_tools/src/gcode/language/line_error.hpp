// SPDX-License-Identifier: MIT
// LineError: a language-layer failure inside one line, before the reader adds file and line.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>

#include <curvestep/core/error.hpp>

namespace curvestep::host::gcode::detail {

/// Thrown by the lexer, parser and evaluator; ProgramReader turns it into a LoadError naming
/// file:line:column.
class LineError : public std::runtime_error {
 public:
  /// `column`: 1-based source column (0 if unknown); `field`: the offending text as written.
  LineError(std::size_t column, std::string field, std::string message, Error code)
      : std::runtime_error(message), column_(column), field_(std::move(field)), message_(std::move(message)), code_(code) {}

  [[nodiscard]] std::size_t column() const noexcept { return column_; }      ///< 1-based column
  [[nodiscard]] const std::string& field() const noexcept { return field_; } ///< the text at fault
  [[nodiscard]] const std::string& message() const noexcept { return message_; } ///< the cause
  [[nodiscard]] Error code() const noexcept { return code_; }                ///< the error code

 private:
  std::size_t column_;
  std::string field_;
  std::string message_;
  Error code_;
};

}  // namespace curvestep::host::gcode::detail
