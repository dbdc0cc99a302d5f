// SPDX-License-Identifier: MIT
// LoadError: why a job or machine file was rejected, naming file, line, segment and field.
#pragma once

#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>

#include <curvestep/core/error.hpp>

namespace curvestep::host {

/// Where in an input file a problem lies. Empty or zero members are unknown.
struct SourceLocation {
  std::string file;                    ///< file name as given (or the name passed to parse_*)
  std::size_t line = 0;                ///< 1-based line, 0 if unknown
  std::size_t column = 0;              ///< 1-based column, 0 if unknown (syntax errors only)
  std::optional<std::size_t> segment;  ///< segment index in the file, counted from 0
  std::string segment_type;            ///< the segment's "type" if known ("bezier")
  std::string field;                   ///< the field at fault, e.g. "points"[2][1]
};

/// A job or machine file could not be loaded. what() is one line:
/// `job.json:14: segment 3 (bezier): "points"[2][1]: value 1e+09 is outside the Q16.16 range`.
class LoadError : public std::runtime_error {
 public:
  /// `code` classifies the failure (InvalidJob, InvalidMachine, FixedOverflow, SegmentsNotConnected, ...).
  LoadError(SourceLocation location, std::string message, Error code);

  /// Where the problem is.
  [[nodiscard]] const SourceLocation& location() const noexcept { return location_; }
  /// The cause alone, without the location prefix.
  [[nodiscard]] const std::string& message() const noexcept { return message_; }
  /// The error code that best describes the failure.
  [[nodiscard]] Error code() const noexcept { return code_; }

 private:
  SourceLocation location_;
  std::string message_;
  Error code_;
};

/// Formats a location and message as LoadError::what() does.
[[nodiscard]] std::string format_load_error(const SourceLocation& location, const std::string& message);

}  // namespace curvestep::host
