// SPDX-License-Identifier: MIT
// The first step of reading a LinuxCNC line: blanks and comments out, letters lower case, each
// remaining character's source column kept for messages.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "line_error.hpp"

namespace curvestep::host::gcode::detail {

/// A comment of the line: the text between ( and ), or after ;.
struct Comment {
  std::size_t column = 0;  ///< 1-based column of '(' or ';'
  std::string body;        ///< the text inside, as written
  bool parenthesised = true; ///< ( ) comment (only those carry MSG, DEBUG, PRINT)
};

/// A line with LinuxCNC's blank removal done.
struct LexedLine {
  std::string text;                  ///< lower case, no blanks, no comments, no leading '/'
  std::vector<std::size_t> columns;  ///< 1-based source column of each character of text
  std::vector<Comment> comments;     ///< in source order
  bool block_delete = false;         ///< the first non-blank character was '/'
  std::optional<LineError> error;    ///< an unclosed or nested comment (raised when the line runs)
  /// 1-based source column of text[index]; one past the last character for index == text.size().
  [[nodiscard]] std::size_t column(std::size_t index) const;
};

/// Lexes one source line (no newline).
[[nodiscard]] LexedLine lex_line(std::string_view source);

}  // namespace curvestep::host::gcode::detail
