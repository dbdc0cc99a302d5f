// SPDX-License-Identifier: MIT
// One LinuxCNC line parsed once: its words, parameter assignments, O-word and messages, each value a
// small expression tree (expression.hpp) evaluated whenever the line runs.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <curvestep/host/gcode/program_block.hpp>

#include "expression.hpp"
#include "lexer.hpp"
#include "line_error.hpp"

namespace curvestep::host::gcode::detail {

/// The O-word keywords. Program: a numbered program's first line, `O100` alone (Fanuc style, as
/// LinuxCNC reads it: the main program's number on the program's first line, else the start of a
/// numbered subprogram that M99 ends and M98 calls).
enum class Keyword : std::uint8_t {
  Sub, Endsub, Return, Call, If, Elseif, Else, Endif, While, Endwhile, Do, Repeat, Endrepeat, Break, Continue, Program
};

/// The keyword as LinuxCNC spells it ("endsub"; empty for Program, which has none).
[[nodiscard]] std::string_view keyword_name(Keyword keyword) noexcept;

/// A word of the line: a letter and its value.
struct WordValue {
  char letter = 0;          ///< upper case
  NodeIndex value = no_node;
  std::size_t column = 0;   ///< 1-based column of the letter
};

/// `#target = value`. The target is a named parameter or a number expression.
struct Assignment {
  std::string name;                  ///< named target (lower case), or empty
  NodeIndex number = no_node;        ///< numbered target: the number's expression
  NodeIndex value = no_node;
  std::size_t column = 0;            ///< column of '#'
  std::size_t end_column = 0;        ///< one past the target (for messages)
};

/// An O-word line: `o<label> keyword [arguments]`.
struct OWord {
  Keyword keyword = Keyword::Sub;
  std::string label;                 ///< "100" or "<name>"; empty if computed (call only)
  NodeIndex label_value = no_node;   ///< computed label of `o[...] call`
  std::vector<NodeIndex> arguments;  ///< call arguments; if/elseif/while/repeat/return/endsub: at most one
  std::size_t column = 0;            ///< column of 'o'
};

/// A message comment, substituted when the line runs.
struct MessageText {
  ProgramMessage::Kind kind = ProgramMessage::Kind::Message;
  std::string text;                  ///< after the comma, as written
};

/// A parsed line. A line that failed to parse keeps its error, raised only if the line runs.
struct ParsedLine {
  bool block_delete = false;
  bool percent = false;              ///< a '%' delimiter line
  std::vector<Node> nodes;           ///< every expression tree of the line
  std::vector<WordValue> words;
  std::vector<Assignment> assignments;
  std::optional<OWord> oword;
  std::vector<MessageText> messages;
  std::optional<LineError> error;
};

/// The word `M<code>` of the line written as a plain number (M98, M099), or null. Only such an M98
/// or M99 is control flow: the structure is found before any value is computed.
[[nodiscard]] const WordValue* literal_m_word(const ParsedLine& line, double code) noexcept;

/// The word `letter` of the line (upper case), or null.
[[nodiscard]] const WordValue* word_of(const ParsedLine& line, char letter) noexcept;

/// True for a line with nothing in it but blanks and plain comments.
[[nodiscard]] bool is_blank(const ParsedLine& line) noexcept;

/// Parses one source line. Syntax errors of an O-word line are thrown (the program's structure
/// depends on them); those of other lines are kept in ParsedLine::error.
[[nodiscard]] ParsedLine parse_program_line(std::string_view source);

}  // namespace curvestep::host::gcode::detail
