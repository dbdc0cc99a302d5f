// SPDX-License-Identifier: MIT
// Internal: errors and warnings of one SVG file, located at an element (file:line: <element id> "attribute": cause).
#pragma once

#include <string>
#include <vector>

#include <tinyxml2.h>

#include <curvestep/core/error.hpp>
#include <curvestep/host/load_error.hpp>

#include "svg_geometry.hpp"

namespace curvestep::host::svg {

/// Throws LoadErrors and collects warnings for the file `file`.
class Diagnostics {
 public:
  explicit Diagnostics(std::string file) : file_(std::move(file)) {}

  /// The file name used in messages.
  [[nodiscard]] const std::string& file() const noexcept { return file_; }

  /// "<path id="wing">".
  [[nodiscard]] static std::string label(const tinyxml2::XMLElement& element);
  /// "<path id="wing"> "d"" (the label alone without an attribute).
  [[nodiscard]] static std::string field(const tinyxml2::XMLElement& element, const char* attribute);

  /// Throws LoadError at `line` naming `field`.
  [[noreturn]] void fail_at(std::size_t line, const std::string& field, const std::string& message,
                            Error code = Error::InvalidJob) const;
  /// Throws LoadError at the element (and attribute, if not empty).
  [[noreturn]] void fail(const tinyxml2::XMLElement& element, const char* attribute, const std::string& message,
                         Error code = Error::InvalidJob) const;
  /// Throws LoadError for malformed attribute text: "at character N: cause".
  [[noreturn]] void fail_syntax(const tinyxml2::XMLElement& element, const char* attribute, const SyntaxError& error) const;

  /// Records "file:line: <element> message".
  void warn(const tinyxml2::XMLElement& element, const std::string& message);
  /// Records a warning located like a LoadError: "file:line: <element> "attribute": message".
  void warn_at(const tinyxml2::XMLElement& element, const char* attribute, const std::string& message);
  /// Records a whole warning line.
  void warn_line(std::string line) { warnings_.push_back(std::move(line)); }

  /// Keeps the next warning's place for one whose text is known only later (a summary), so the
  /// warnings stay in document order. A place never filled is dropped by take_warnings.
  [[nodiscard]] std::size_t reserve_warning() {
    warnings_.emplace_back();
    return warnings_.size() - 1;
  }
  /// Fills a reserved place with warn()'s line for `element`.
  void warn_in(std::size_t place, const tinyxml2::XMLElement& element, const std::string& message);

  /// The warnings so far, moved out.
  [[nodiscard]] std::vector<std::string> take_warnings();

 private:
  [[nodiscard]] std::string line(const tinyxml2::XMLElement& element, const std::string& message) const;

  std::string file_;
  std::vector<std::string> warnings_;
};

}  // namespace curvestep::host::svg
