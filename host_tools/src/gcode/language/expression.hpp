// SPDX-License-Identifier: MIT
// LinuxCNC real values: numbers, #parameters, [expressions] and functions, parsed once into a small
// tree per line and evaluated each time the line runs.
//
// Precedence (LinuxCNC's, highest first; left to right within a level):
//   **  |  * / MOD  |  + -  |  EQ NE GT GE LT LE  |  AND OR XOR
// A sign written before a value belongs to that value, so [-2**2] is 4, as in LinuxCNC.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "lexer.hpp"

namespace curvestep::host::gcode::detail {

/// What a node of the tree computes.
enum class NodeKind : std::uint8_t { Number, Numbered, Named, Exists, Negate, Function, Atan, Binary };
/// The one-argument functions (angles in degrees).
enum class Function : std::uint8_t { Abs, Acos, Asin, Cos, Exp, Fix, Fup, Ln, Round, Sin, Sqrt, Tan };
/// The binary operators.
enum class Operator : std::uint8_t { Power, Times, Divide, Modulo, Plus, Minus, Eq, Ne, Gt, Ge, Lt, Le, And, Or, Xor };

/// Index of a node in its line's node list.
using NodeIndex = std::uint32_t;
inline constexpr NodeIndex no_node = 0xFFFFFFFFu;

/// One node; `first`/`second` are children (Numbered: the number expression; Atan: y, x).
struct Node {
  NodeKind kind = NodeKind::Number;
  Function function = Function::Abs;
  Operator op = Operator::Plus;
  double number = 0;          ///< Number
  std::string name;           ///< Named, Exists: lower case, no blanks
  NodeIndex first = no_node;
  NodeIndex second = no_node;
  std::size_t begin_column = 0;  ///< source columns [begin, end) the node was written in
  std::size_t end_column = 0;
};

/// Reads text of a lexed line left to right, failing with the source columns.
class Cursor {
 public:
  Cursor(const LexedLine& line, std::string_view source) : line_(line), source_(source) {}
  [[nodiscard]] bool at_end() const noexcept { return position_ >= line_.text.size(); }
  [[nodiscard]] char peek(std::size_t ahead = 0) const noexcept {
    return position_ + ahead < line_.text.size() ? line_.text[position_ + ahead] : '\0';
  }
  void advance(std::size_t count = 1) noexcept { position_ += count; }
  [[nodiscard]] std::size_t position() const noexcept { return position_; }
  [[nodiscard]] bool starts_with(std::string_view word) const noexcept {
    return line_.text.compare(position_, word.size(), word) == 0;
  }
  /// 1-based source column of text[index].
  [[nodiscard]] std::size_t column(std::size_t index) const { return line_.column(index); }
  /// Source column just after text[index - 1].
  [[nodiscard]] std::size_t end_column(std::size_t index) const { return index == 0 ? 1 : line_.column(index - 1) + 1; }
  /// The source text between two columns ([begin, end), 1-based).
  [[nodiscard]] std::string source_text(std::size_t begin_column, std::size_t end_column) const;
  /// Throws LineError at text[begin_index] naming the text from begin_index to here (at least one char).
  [[noreturn]] void fail(std::size_t begin_index, const std::string& message, Error code) const;

 private:
  const LexedLine& line_;
  std::string_view source_;
  std::size_t position_ = 0;
};

/// Parses one real value at the cursor (a number, #parameter, [expression], unary function or a
/// signed one of these), appends its nodes and returns the root.
[[nodiscard]] NodeIndex parse_real_value(Cursor& cursor, std::vector<Node>& nodes);
/// Parses a named parameter reference after "#<" up to '>'; returns the lower-case name.
[[nodiscard]] std::string parse_parameter_name(Cursor& cursor);

/// Where evaluation reads parameters.
class ParameterSource {
 public:
  /// #number (already checked to be 1..5602).
  [[nodiscard]] virtual double numbered(int number) const = 0;
  /// #<name>, nullopt if it does not exist (local or global by the leading '_').
  [[nodiscard]] virtual std::optional<double> named(const std::string& name) const = 0;

 protected:
  ~ParameterSource() = default;
};

/// The value of nodes[root]; throws LineError naming the sub-expression at fault (division by zero,
/// SQRT of a negative number, an undefined named parameter, ...). `source` is the line as written.
[[nodiscard]] double evaluate(const std::vector<Node>& nodes, NodeIndex root, std::string_view source,
                              const ParameterSource& parameters);

/// A parameter number from its evaluated value: an integer 1..5602 (ParameterStore::max_numbered).
[[nodiscard]] int parameter_number(double value, const Node& at, std::string_view source);

/// The source text of a node, cut for messages.
[[nodiscard]] std::string node_text(const Node& node, std::string_view source);

}  // namespace curvestep::host::gcode::detail
