// SPDX-License-Identifier: MIT
// The allocation-free G-code line parser: numbers, words, comments, line numbers and its errors.
#include <catch2/catch.hpp>

#include <cstddef>
#include <random>
#include <string>
#include <string_view>

#include <curvestep/gcode.hpp>

#include "support/numeric.hpp"

using namespace curvestep;
using namespace curvestep::gcode;

namespace {

Result<double> number(std::string_view text) {
  std::size_t position = 0;
  return parse_number(text, position);
}

}  // namespace

TEST_CASE("gcode parser: numbers are the correctly rounded doubles of their decimals", "[gcode][parser]") {
  // Expected values are C++ literals, which the compiler rounds correctly.
  CHECK(number("0").value() == 0.0);
  CHECK(number("12").value() == 12.0);
  CHECK(number("-1.5").value() == -1.5);
  CHECK(number("+.5").value() == 0.5);
  CHECK(number("5.").value() == 5.0);
  CHECK(number("0.1").value() == 0.1);
  CHECK(number("-0.0001").value() == -0.0001);
  CHECK(number("3.14159265358979").value() == 3.14159265358979);
  CHECK(number("123456789.012345").value() == 123456789.012345);
  CHECK(number("0.30000000000000000000").value() == 0.3);  // trailing zeros beyond 15 digits are harmless
  CHECK(number("  - 2.25").value() == -2.25);              // blanks before the number and after the sign
  CHECK(number("1 2.5 0").value() == 12.5);                // and between the digits (LinuxCNC removes blanks)
}

TEST_CASE("gcode parser: fraction digits beyond 15 significant are rounded off by the first one dropped", "[gcode][parser]") {
  // The expected values are the 15-digit decimals, rounded by hand, as C++ literals.
  CHECK(number("0.30000000000000004").value() == 0.3);                   // Python's repr of 0.1 + 0.2
  CHECK(number("0.1234567890123456").value() == 0.123456789012346);      // 16th digit 6: up
  CHECK(number("0.1234567890123444").value() == 0.123456789012344);      // 16th digit 4: down
  CHECK(number("-1.99999999999999999").value() == -2.0);                 // the carry runs through
  CHECK(number("12.3456789012345678").value() == 12.3456789012346);
  CHECK(number("0.00000000000000000000001").value() == 0.0);             // beyond 22 decimals, 1 < 5
  CHECK(number("0.00000000000000000000006").value() == 1e-22);
}

TEST_CASE("gcode parser: a number with no digit or an integer part beyond 15 digits is GcodeBadNumber at its column", "[gcode][parser]") {
  for (const std::string_view bad : {"", "-", ".", "+.", "1234567890123456", "-12345678901234567.5"}) {
    INFO(bad);
    const auto r = number(bad);
    REQUIRE_FALSE(r);
    CHECK(r.error() == Error::GcodeBadNumber);
    CHECK(r.where() == 1);
  }
}

TEST_CASE("gcode parser: G and M codes keep their value in tenths", "[gcode][parser]") {
  CHECK(code_tenths(0.0) == 0);
  CHECK(code_tenths(5.0) == 50);
  CHECK(code_tenths(number("5.1").value()) == 51);
  CHECK(code_tenths(number("5.2").value()) == 52);
  CHECK(code_tenths(number("91.1").value()) == 911);
  CHECK(code_tenths(number("5.25").value()) == -1);
  CHECK(code_tenths(-1.0) == -1);
}

TEST_CASE("gcode parser: a line becomes words with letters, values and columns", "[gcode][parser]") {
  const auto block = parse_line("N10 g1 x1.5 Y-2 (move) F600 ; comment X9");
  REQUIRE(block);
  const auto& b = block.value();
  CHECK(b.has_line_number());
  CHECK(b.line_number() == 10.0);
  REQUIRE(b.size() == 4);
  CHECK(b.words()[0].letter == 'G');
  CHECK(b.words()[0].code_tenths == 10);
  CHECK(b.words()[0].column == 5);
  CHECK(b.words()[1].letter == 'X');
  CHECK(b.words()[1].value == 1.5);
  CHECK(b.words()[1].column == 8);
  CHECK(b.words()[2].letter == 'Y');
  CHECK(b.words()[2].value == -2.0);
  CHECK(b.words()[2].column == 13);
  CHECK(b.words()[3].letter == 'F');
  CHECK(b.words()[3].value == 600.0);
  CHECK(b.find('Z') == nullptr);
}

TEST_CASE("gcode parser: blank lines, comments and the percent delimiter hold no words", "[gcode][parser]") {
  for (const std::string_view line : {"", "   ", "(only a comment)", "; semicolon comment", "%", "  %  ", "% (program start)", "\r"}) {
    INFO(line);
    const auto block = parse_line(line);
    REQUIRE(block);
    CHECK(block.value().empty());
  }
}

TEST_CASE("gcode parser: letters and blanks between letter and number", "[gcode][parser]") {
  const auto block = parse_line("G 2 X 1 Y1");
  REQUIRE(block);
  REQUIRE(block.value().size() == 3);
  CHECK(block.value().words()[0].code_tenths == 20);
  CHECK(block.value().words()[1].value == 1.0);
}

TEST_CASE("gcode parser: errors name the column of the word at fault", "[gcode][parser]") {
  struct Case {
    std::string_view line;
    Error code;
    std::size_t column;
  };
  const Case cases[] = {
      {"G1 A5", Error::GcodeUnsupportedWord, 4},      // unknown axis letter
      {"G1 X1 E2", Error::GcodeUnsupportedWord, 7},   // an extruder word
      {"G1 /X1", Error::GcodeSyntax, 4},              // block delete only first on the line
      {"G1 X1 X2", Error::GcodeConflictingWords, 7},  // X twice
      {"G1 X1 N5", Error::GcodeSyntax, 7},            // N not first
      {"G1 X1 (open", Error::GcodeSyntax, 7},         // unclosed comment
      {"G1 (a (nested) one) X1", Error::GcodeSyntax, 7},
      {"G1 X1 #1=2", Error::GcodeSyntax, 7},          // parameters are not supported
      {"G1 X", Error::GcodeBadNumber, 4},             // letter without number
      {"G1 X1.2.3", Error::GcodeSyntax, 8},           // second decimal point
      {"G1 X12345678901234567", Error::GcodeBadNumber, 4},
      {"% G1", Error::GcodeSyntax, 3},
      {"%(start) X1", Error::GcodeSyntax, 10},
  };
  for (const auto& c : cases) {
    INFO(c.line);
    const auto block = parse_line(c.line);
    REQUIRE_FALSE(block);
    CHECK(block.error() == c.code);
    CHECK(block.where() == c.column);
  }
}

TEST_CASE("gcode parser: a line with more words than the capacity is refused, not truncated", "[gcode][parser]") {
  const auto block = parse_line<2>("G1 X1 Y2");
  REQUIRE_FALSE(block);
  CHECK(block.error() == Error::GcodeSyntax);
  CHECK(block.where() == 7);
}

TEST_CASE("gcode parser: random lines never crash and every failure points inside the line", "[gcode][parser][property]") {
  // Lines drawn from G-code's own characters plus a few strangers; the parser and the interpreter
  // must either accept a line or name a column of it (1 .. size).
  std::mt19937 random(curvestep::testing::test_seed());
  constexpr std::string_view alphabet = "GMXYZIJKRPQLFN0123456789.-+ ()%;/#$abxyzgTS\t";
  std::uniform_int_distribution<std::size_t> pick(0, alphabet.size() - 1);
  std::uniform_int_distribution<std::size_t> length(0, 40);
  Interpreter<8> machine;
  const int count = curvestep::testing::test_count(20000);
  int accepted = 0;
  for (int n = 0; n < count; ++n) {
    std::string line;
    const std::size_t size = length(random);
    for (std::size_t i = 0; i < size; ++i) line += alphabet[pick(random)];
    INFO(line);
    const auto block = parse_line(line);
    if (!block) {
      REQUIRE(block.where() >= 1);
      REQUIRE(block.where() <= line.size());
      continue;
    }
    const auto motion = machine.execute(block.value());
    if (!motion) {
      REQUIRE(motion.where() >= 1);
      REQUIRE(motion.where() <= line.size());
      if (machine.in_nurbs_block() && motion.error() == Error::GcodeNurbsBlock) machine = Interpreter<8>{};
      continue;
    }
    ++accepted;
  }
  CHECK(accepted > 0);
}

// The parser is constexpr: a line can be checked at compile time.
static_assert(parse_line("N5 G1 X1.5 (c) Y-2").value().size() == 3);
static_assert(parse_line("G5.2 P1 L3").value().words()[0].code_tenths == 52);
static_assert(!parse_line("G1 A1"));
