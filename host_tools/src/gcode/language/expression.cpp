// SPDX-License-Identifier: MIT
// Real values and expressions: a recursive-descent parser over LinuxCNC's five precedence levels,
// and an evaluator that checks every operation LinuxCNC refuses (division by zero, SQRT and LN
// outside their domain, ACOS/ASIN beyond ±1) and every result that is not finite.
#include "expression.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <numbers>
#include <string_view>
#include <utility>

#include <curvestep/host/gcode/program_block.hpp>
#include <curvestep/host/printable.hpp>

namespace curvestep::host::gcode::detail {
namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_letter(char c) { return c >= 'a' && c <= 'z'; }

/// Two values are equal within LinuxCNC's documented TOLERANCE_EQUAL (1e-6).
constexpr double equal_tolerance = 1e-6;
constexpr double degrees_per_radian = 180.0 / std::numbers::pi;

struct OperatorSpelling {
  std::string_view text;
  Operator op;
  int level;  ///< 0 binds tightest
};

// "**" before "*": the first spelling that matches wins.
constexpr std::array<OperatorSpelling, 15> operators{{
    {"**", Operator::Power, 0},  {"*", Operator::Times, 1},  {"/", Operator::Divide, 1}, {"mod", Operator::Modulo, 1},
    {"+", Operator::Plus, 2},    {"-", Operator::Minus, 2},  {"eq", Operator::Eq, 3},    {"ne", Operator::Ne, 3},
    {"gt", Operator::Gt, 3},     {"ge", Operator::Ge, 3},    {"lt", Operator::Lt, 3},    {"le", Operator::Le, 3},
    {"and", Operator::And, 4},   {"or", Operator::Or, 4},    {"xor", Operator::Xor, 4},
}};
constexpr int lowest_level = 4;

struct FunctionSpelling {
  std::string_view text;
  Function function;
};

constexpr std::array<FunctionSpelling, 12> functions{{
    {"abs", Function::Abs}, {"acos", Function::Acos}, {"asin", Function::Asin}, {"cos", Function::Cos},
    {"exp", Function::Exp}, {"fix", Function::Fix},   {"fup", Function::Fup},   {"ln", Function::Ln},
    {"round", Function::Round}, {"sin", Function::Sin}, {"sqrt", Function::Sqrt}, {"tan", Function::Tan},
}};

NodeIndex add(std::vector<Node>& nodes, Node node) {
  nodes.push_back(std::move(node));
  return static_cast<NodeIndex>(nodes.size() - 1);
}

NodeIndex parse_level(Cursor& cursor, std::vector<Node>& nodes, int level);

/// "[" expression "]" at the cursor.
NodeIndex parse_bracketed(Cursor& cursor, std::vector<Node>& nodes) {
  const std::size_t open = cursor.position();
  if (cursor.peek() != '[') cursor.fail(open, "'[' expected", Error::GcodeSyntax);
  cursor.advance();
  const NodeIndex root = parse_level(cursor, nodes, lowest_level);
  if (cursor.peek() != ']') {
    if (is_letter(cursor.peek())) {
      const std::size_t start = cursor.position();
      while (is_letter(cursor.peek())) cursor.advance();
      cursor.fail(start, "unknown operator (binary operators: ** * / MOD + - EQ NE GT GE LT LE AND OR XOR)", Error::GcodeSyntax);
    }
    if (cursor.at_end()) cursor.fail(open, "the expression is not closed: ']' missing", Error::GcodeSyntax);
    cursor.fail(cursor.position(), "an operator or ']' expected", Error::GcodeSyntax);
  }
  cursor.advance();
  return root;
}

const OperatorSpelling* match_operator(const Cursor& cursor) {
  for (const auto& spelling : operators) {
    if (cursor.starts_with(spelling.text)) return &spelling;
  }
  return nullptr;
}

NodeIndex parse_level(Cursor& cursor, std::vector<Node>& nodes, int level) {
  if (level < 0) return parse_real_value(cursor, nodes);
  NodeIndex left = parse_level(cursor, nodes, level - 1);
  for (;;) {
    const OperatorSpelling* spelling = match_operator(cursor);
    if (spelling == nullptr || spelling->level != level) return left;
    cursor.advance(spelling->text.size());
    const NodeIndex right = parse_level(cursor, nodes, level - 1);
    Node node;
    node.kind = NodeKind::Binary;
    node.op = spelling->op;
    node.first = left;
    node.second = right;
    node.begin_column = nodes[left].begin_column;
    node.end_column = nodes[right].end_column;
    left = add(nodes, std::move(node));
  }
}

NodeIndex parse_number(Cursor& cursor, std::vector<Node>& nodes) {
  const std::size_t start = cursor.position();
  bool negative = false;
  if (cursor.peek() == '+' || cursor.peek() == '-') {
    negative = cursor.peek() == '-';
    cursor.advance();
  }
  std::string digits;
  bool point = false;
  bool any_digit = false;
  for (;;) {
    const char c = cursor.peek();
    if (is_digit(c)) {
      any_digit = true;
    } else if (c == '.' && !point) {
      point = true;
    } else {
      break;
    }
    digits += c;
    cursor.advance();
  }
  if (!any_digit) {
    if (cursor.at_end() && cursor.position() == start) {
      cursor.fail(start == 0 ? 0 : start - 1, "a value is missing (a number, #parameter or [expression])", Error::GcodeBadNumber);
    }
    cursor.fail(start, "a number, #parameter or [expression] expected", Error::GcodeBadNumber);
  }
  double value = 0;
  const auto result = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (result.ec != std::errc{} || !std::isfinite(value)) cursor.fail(start, "number out of range", Error::GcodeBadNumber);
  Node node;
  node.number = negative ? -value : value;
  node.begin_column = cursor.column(start);
  node.end_column = cursor.end_column(cursor.position());
  return add(nodes, std::move(node));
}

NodeIndex parse_function(Cursor& cursor, std::vector<Node>& nodes) {
  const std::size_t start = cursor.position();
  std::string name;
  while (is_letter(cursor.peek())) {
    name += cursor.peek();
    cursor.advance();
  }
  Node node;
  node.begin_column = cursor.column(start);
  if (name == "atan") {
    node.kind = NodeKind::Atan;
    node.first = parse_bracketed(cursor, nodes);
    if (cursor.peek() != '/' || cursor.peek(1) != '[') cursor.fail(start, "ATAN takes two arguments: ATAN[y]/[x]", Error::GcodeSyntax);
    cursor.advance();
    node.second = parse_bracketed(cursor, nodes);
  } else if (name == "exists") {
    node.kind = NodeKind::Exists;
    if (!cursor.starts_with("[#<")) cursor.fail(start, "EXISTS takes a named parameter: EXISTS[#<name>]", Error::GcodeSyntax);
    cursor.advance(3);
    node.name = parse_parameter_name(cursor);
    if (cursor.peek() != ']') cursor.fail(start, "EXISTS takes a named parameter: EXISTS[#<name>]", Error::GcodeSyntax);
    cursor.advance();
  } else {
    bool known = false;
    for (const auto& spelling : functions) {
      if (spelling.text == name) {
        node.function = spelling.function;
        known = true;
      }
    }
    if (!known || cursor.peek() != '[') {
      cursor.fail(start, known ? "a function's argument is written in brackets: " + name + "[...]"
                               : "not a number, parameter, expression or function (functions: ABS ACOS ASIN ATAN COS EXISTS EXP "
                                 "FIX FUP LN ROUND SIN SQRT TAN)",
                  Error::GcodeSyntax);
    }
    node.kind = NodeKind::Function;
    node.first = parse_bracketed(cursor, nodes);
  }
  node.end_column = cursor.end_column(cursor.position());
  return add(nodes, std::move(node));
}

[[noreturn]] void fail_at(const Node& node, std::string_view source, const std::string& message, Error code) {
  throw LineError(node.begin_column, node_text(node, source), message, code);
}

double checked(double value, const Node& node, std::string_view source) {
  if (!std::isfinite(value)) fail_at(node, source, "the result is not a finite number", Error::GcodeBadNumber);
  return value;
}

double apply(Function function, double x, const Node& node, std::string_view source) {
  switch (function) {
    case Function::Abs: return std::fabs(x);
    case Function::Acos:
      if (x < -1.0 || x > 1.0) fail_at(node, source, "ACOS of a value outside -1..1", Error::GcodeBadNumber);
      return std::acos(x) * degrees_per_radian;
    case Function::Asin:
      if (x < -1.0 || x > 1.0) fail_at(node, source, "ASIN of a value outside -1..1", Error::GcodeBadNumber);
      return std::asin(x) * degrees_per_radian;
    case Function::Cos: return std::cos(x / degrees_per_radian);
    case Function::Exp: return std::exp(x);
    case Function::Fix: return std::floor(x);
    case Function::Fup: return std::ceil(x);
    case Function::Ln:
      if (x <= 0.0) fail_at(node, source, "LN of zero or a negative value", Error::GcodeBadNumber);
      return std::log(x);
    case Function::Round: return std::round(x);
    case Function::Sin: return std::sin(x / degrees_per_radian);
    case Function::Sqrt:
      if (x < 0.0) fail_at(node, source, "SQRT of a negative value", Error::GcodeBadNumber);
      return std::sqrt(x);
    case Function::Tan: return std::tan(x / degrees_per_radian);
  }
  return x;
}

double truth(bool value) { return value ? 1.0 : 0.0; }

double apply(Operator op, double a, double b, const Node& node, std::string_view source) {
  switch (op) {
    case Operator::Power:
      if (a < 0.0 && b != std::floor(b)) fail_at(node, source, "a negative value raised to a non-integer power", Error::GcodeBadNumber);
      if (a == 0.0 && b < 0.0) fail_at(node, source, "zero raised to a negative power", Error::DivisionByZero);
      return std::pow(a, b);
    case Operator::Times: return a * b;
    case Operator::Divide:
      if (b == 0.0) fail_at(node, source, "division by zero", Error::DivisionByZero);
      return a / b;
    case Operator::Modulo: {
      if (b == 0.0) fail_at(node, source, "MOD by zero", Error::DivisionByZero);
      // LinuxCNC: the remainder of a truncated division, made non-negative by adding |b|.
      const double r = std::fmod(a, b);
      return r < 0.0 ? r + std::fabs(b) : r;
    }
    case Operator::Plus: return a + b;
    case Operator::Minus: return a - b;
    case Operator::Eq: return truth(std::fabs(a - b) < equal_tolerance);
    case Operator::Ne: return truth(!(std::fabs(a - b) < equal_tolerance));
    case Operator::Gt: return truth(a > b);
    case Operator::Ge: return truth(a > b || std::fabs(a - b) < equal_tolerance);
    case Operator::Lt: return truth(a < b);
    case Operator::Le: return truth(a < b || std::fabs(a - b) < equal_tolerance);
    case Operator::And: return truth(a != 0.0 && b != 0.0);
    case Operator::Or: return truth(a != 0.0 || b != 0.0);
    case Operator::Xor: return truth((a != 0.0) != (b != 0.0));
  }
  return 0;
}

}  // namespace

std::string Cursor::source_text(std::size_t begin_column, std::size_t end_column) const {
  if (begin_column == 0 || begin_column > source_.size() + 1 || end_column <= begin_column) return {};
  return std::string(source_.substr(begin_column - 1, end_column - begin_column));
}

void Cursor::fail(std::size_t begin_index, const std::string& message, Error code) const {
  const std::size_t begin = column(begin_index);
  const std::size_t end = std::max(end_column(position_), begin + 1);
  throw LineError(begin, quoted_excerpt(source_text(begin, end)), message, code);
}

std::string parse_parameter_name(Cursor& cursor) {
  const std::size_t start = cursor.position();
  std::string name;
  while (!cursor.at_end() && cursor.peek() != '>') {
    name += cursor.peek();
    cursor.advance();
  }
  if (cursor.at_end()) cursor.fail(start == 0 ? 0 : start - 1, "a parameter name is not closed: '>' missing", Error::GcodeSyntax);
  if (name.empty()) cursor.fail(start == 0 ? 0 : start - 1, "empty parameter name", Error::GcodeSyntax);
  cursor.advance();
  return name;
}

NodeIndex parse_real_value(Cursor& cursor, std::vector<Node>& nodes) {
  const std::size_t start = cursor.position();
  const char c = cursor.peek();
  if (c == '[') {
    const NodeIndex inner = parse_bracketed(cursor, nodes);
    // The brackets belong to the value, so messages quote them.
    nodes[inner].begin_column = cursor.column(start);
    nodes[inner].end_column = cursor.end_column(cursor.position());
    return inner;
  }
  if (c == '#') {
    cursor.advance();
    Node node;
    node.begin_column = cursor.column(start);
    if (cursor.peek() == '<') {
      cursor.advance();
      node.kind = NodeKind::Named;
      node.name = parse_parameter_name(cursor);
    } else {
      node.kind = NodeKind::Numbered;
      node.first = parse_real_value(cursor, nodes);
    }
    node.end_column = cursor.end_column(cursor.position());
    return add(nodes, std::move(node));
  }
  if ((c == '+' || c == '-') && !is_digit(cursor.peek(1)) && cursor.peek(1) != '.') {
    cursor.advance();
    const NodeIndex operand = parse_real_value(cursor, nodes);
    if (c == '+') return operand;
    Node node;
    node.kind = NodeKind::Negate;
    node.first = operand;
    node.begin_column = cursor.column(start);
    node.end_column = nodes[operand].end_column;
    return add(nodes, std::move(node));
  }
  if (is_letter(c)) return parse_function(cursor, nodes);
  return parse_number(cursor, nodes);
}

std::string node_text(const Node& node, std::string_view source) {
  if (node.begin_column == 0 || node.begin_column > source.size() || node.end_column <= node.begin_column) return {};
  return quoted_excerpt(source.substr(node.begin_column - 1, node.end_column - node.begin_column));
}

int parameter_number(double value, const Node& at, std::string_view source) {
  const double rounded = std::round(value);
  if (std::fabs(value - rounded) > 1e-4) fail_at(at, source, "a parameter number must be an integer", Error::GcodeBadNumber);
  if (rounded < 1 || rounded > ParameterStore::max_numbered) {
    fail_at(at, source, "parameter numbers run from 1 to " + std::to_string(ParameterStore::max_numbered), Error::GcodeBadNumber);
  }
  return static_cast<int>(rounded);
}

double evaluate(const std::vector<Node>& nodes, NodeIndex root, std::string_view source, const ParameterSource& parameters) {
  const Node& node = nodes[root];
  switch (node.kind) {
    case NodeKind::Number: return node.number;
    case NodeKind::Numbered:
      return parameters.numbered(parameter_number(evaluate(nodes, node.first, source, parameters), node, source));
    case NodeKind::Named: {
      const auto value = parameters.named(node.name);
      if (!value) fail_at(node, source, "named parameter #<" + node.name + "> is not defined", Error::GcodeSyntax);
      return *value;
    }
    case NodeKind::Exists: return truth(parameters.named(node.name).has_value());
    case NodeKind::Negate: return -evaluate(nodes, node.first, source, parameters);
    case NodeKind::Function:
      return checked(apply(node.function, evaluate(nodes, node.first, source, parameters), node, source), node, source);
    case NodeKind::Atan: {
      const double y = evaluate(nodes, node.first, source, parameters);
      const double x = evaluate(nodes, node.second, source, parameters);
      return std::atan2(y, x) * degrees_per_radian;
    }
    case NodeKind::Binary: {
      const double a = evaluate(nodes, node.first, source, parameters);
      const double b = evaluate(nodes, node.second, source, parameters);
      return checked(apply(node.op, a, b, node, source), node, source);
    }
  }
  return 0;
}

}  // namespace curvestep::host::gcode::detail
