// SPDX-License-Identifier: MIT
// The language layer's lines and parameters: comments and messages, block delete, %, numbered and
// named parameters, indirection, assignment at the end of the line, and the machine layer writing
// system parameters between blocks.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "program_run.hpp"

using namespace curvestep;
using namespace curvestep::host;
using namespace curvestep::host::gcode;
using namespace curvestep::testing;

TEST_CASE("language: words come out upper case with their source columns, N is dropped", "[gcode][language][lines]") {
  const auto blocks = run_program("n10 g1 x1.5 y-2 f300\n  G5.1 X1 I2 J3 ; comment\nm2");
  REQUIRE(blocks.size() == 3);
  const auto& b = blocks[0];
  CHECK(b.line == 1);
  CHECK(b.source == "n10 g1 x1.5 y-2 f300");
  REQUIRE(b.words.size() == 4);
  CHECK(b.words[0].letter == 'G');
  CHECK(b.words[0].value == 1.0);
  CHECK(b.words[0].column == 5);
  CHECK(b.words[1].letter == 'X');
  CHECK(b.words[1].value == 1.5);
  CHECK(b.words[1].column == 8);
  CHECK(b.words[2].value == -2.0);
  CHECK(word(blocks[1], 'G') == 5.1);
  CHECK(blocks[1].words[0].column == 3);
  CHECK(blocks[2].line == 3);
}

TEST_CASE("language: blanks are removed everywhere outside comments (LinuxCNC)", "[gcode][language][lines]") {
  const auto blocks = run_program("G 1 X 1 2 . 5 Y - 3");
  REQUIRE(blocks.size() == 1);
  CHECK(word(blocks[0], 'X') == 12.5);
  CHECK(word(blocks[0], 'Y') == -3.0);
  CHECK(blocks[0].words[1].column == 5);
}

TEST_CASE("language: comments, MSG, DEBUG and PRINT", "[gcode][language][lines]") {
  const auto blocks = run_program(
      "#1 = 2.5 #<_depth> = -1\n"
      "(a plain comment) G0 X1 (another)\n"
      "(MSG, Change the tool)\n"
      "( debug , depth #<_depth> at #1 of #<_missing>)\n"
      "(PRINT,#1#2)\n"
      "#3=7 (DEBUG,#3)\n"
      "; (MSG, not a message after a semicolon)\n");
  REQUIRE(blocks.size() == 5);
  CHECK(blocks[0].messages.empty());
  CHECK(word(blocks[0], 'X') == 1.0);
  REQUIRE(blocks[1].messages.size() == 1);
  CHECK(blocks[1].messages[0].kind == ProgramMessage::Kind::Message);
  CHECK(blocks[1].messages[0].text == " Change the tool");
  CHECK(blocks[1].words.empty());
  CHECK(blocks[2].messages[0].kind == ProgramMessage::Kind::Debug);
  CHECK(blocks[2].messages[0].text == " depth -1.000000 at 2.500000 of #<_missing>");
  CHECK(blocks[3].messages[0].kind == ProgramMessage::Kind::Print);
  CHECK(blocks[3].messages[0].text == "2.5000000.000000");
  CHECK(blocks[4].messages[0].text == "7.000000");  // the comment acts after the line's assignment
}

TEST_CASE("language: block delete is off, so '/' lines run and are marked, on skips them", "[gcode][language][lines]") {
  const std::string program = "G0 X1\n/G0 X2\n  / G0 X3\n";
  const auto off = run_program(program);
  REQUIRE(off.size() == 3);
  CHECK_FALSE(off[0].block_delete);
  CHECK(off[1].block_delete);
  CHECK(off[2].block_delete);
  CHECK(off[2].words[0].column == 5);
  ProgramOptions on;
  on.block_delete = true;
  CHECK(x_values(run_program(program, on)) == std::vector<double>{1.0});
}

TEST_CASE("language: % opens the program and the next % ends it", "[gcode][language][lines]") {
  CHECK(x_values(run_program("\n%\nG0 X1\n%\nG0 X2\n")) == std::vector<double>{1.0});
  CHECK(x_values(run_program("G0 X1\n%\nG0 X2\n")) == std::vector<double>{1.0, 2.0});  // not first: ignored
  CHECK(x_values(run_program("%\nG0 X1\n%\no1 endif\n")) == std::vector<double>{1.0});  // nothing read after the closing %
}

TEST_CASE("language: M2 and M30 end the program after their block", "[gcode][language][lines]") {
  ProgramReader reader("G0 X1\nM30\nG0 X2\n", "end.ngc");
  REQUIRE(reader.next());
  const auto end = reader.next();
  REQUIRE(end);
  CHECK(word(*end, 'M') == 30.0);
  CHECK(reader.ended());
  CHECK_FALSE(reader.next());
}

TEST_CASE("language: numbered parameters read 0 until set, ## and #[...] are indirect", "[gcode][language][parameters]") {
  const auto blocks = run_program(
      "G1 X#31\n"
      "#1 = 5\n"
      "#5 = 7\n"
      "G1 X##1\n"
      "#[1 + 2] = 4\n"
      "G1 X#3 Y#[#1 - 2]\n");
  REQUIRE(blocks.size() == 3);
  CHECK(word(blocks[0], 'X') == 0.0);
  CHECK(word(blocks[1], 'X') == 7.0);
  CHECK(word(blocks[2], 'X') == 4.0);
  CHECK(word(blocks[2], 'Y') == 4.0);
}

TEST_CASE("language: assignments take effect at the end of the line, after every read", "[gcode][language][parameters]") {
  const auto blocks = run_program(
      "#1 = 1\n"
      "#1 = 2 #2 = #1 G1 X#1\n"
      "G1 X#1 Y#2\n"
      "#<a> = 1\n"
      "#<a> = [#<a> + 1] #<b> = #<a>\n"
      "G1 X#<a> Y#<b>\n");
  REQUIRE(blocks.size() == 3);
  CHECK(word(blocks[0], 'X') == 1.0);  // the old #1
  CHECK(word(blocks[1], 'X') == 2.0);
  CHECK(word(blocks[1], 'Y') == 1.0);  // #2 read #1 before the line's assignments
  CHECK(word(blocks[2], 'X') == 2.0);
  CHECK(word(blocks[2], 'Y') == 1.0);
}

TEST_CASE("language: named parameters: case-insensitive, blanks ignored, EXISTS", "[gcode][language][parameters]") {
  const auto blocks = run_program(
      "#<Feed Rate> = 300\n"
      "#<_global> = 2\n"
      "G1 F#<feedrate> X#<_GLOBAL> Y EXISTS[#<nothing>] Z EXISTS[#<feed rate>]\n");
  REQUIRE(blocks.size() == 1);
  CHECK(word(blocks[0], 'F') == 300.0);
  CHECK(word(blocks[0], 'X') == 2.0);
  CHECK(word(blocks[0], 'Y') == 0.0);
  CHECK(word(blocks[0], 'Z') == 1.0);
}

TEST_CASE("language: the machine layer writes system parameters between blocks", "[gcode][language][parameters]") {
  ProgramReader reader("G1 X10\nG1 X[#5420 + 1] Y#<_x>\n", "machine.ngc");
  const auto first = reader.next();
  REQUIRE(first);
  reader.parameters().set(5420, word(*first, 'X'));
  reader.parameters().set_named("_x", 10);
  const auto second = reader.next();
  REQUIRE(second);
  CHECK(word(*second, 'X') == 11.0);
  CHECK(word(*second, 'Y') == 10.0);
}

TEST_CASE("language: parameter errors", "[gcode][language][parameters][errors]") {
  SECTION("an undefined named parameter") {
    const LoadError e = program_error("G0 X1\nG1 X#<depth>");
    CHECK(e.code() == Error::GcodeSyntax);
    CHECK(e.location().line == 2);
    CHECK(e.location().column == 5);
    CHECK(e.location().field == "#<depth>");
    CHECK(e.message() == "named parameter #<depth> is not defined");
  }
  SECTION("a parameter number out of range") { CHECK(program_error("G1 X#5603").code() == Error::GcodeBadNumber); }
  SECTION("parameter 0") { CHECK(program_error("G1 X#0").code() == Error::GcodeBadNumber); }
  SECTION("a parameter number that is not an integer") { CHECK(program_error("G1 X#[1.5]").code() == Error::GcodeBadNumber); }
  SECTION("the machine's parameters are read-only") {
    const LoadError e = program_error("#5420 = 1");
    CHECK(e.code() == Error::GcodeBadNumber);
    CHECK(e.location().column == 1);
  }
  SECTION("a parameter alone, not set") { CHECK(program_error("#1").code() == Error::GcodeSyntax); }
  SECTION("an unclosed comment") {
    const LoadError e = program_error("G1 X1 (no end");
    CHECK(e.code() == Error::GcodeSyntax);
    CHECK(e.location().column == 7);
  }
  SECTION("a nested comment") { CHECK(program_error("G1 (a (b) c)").code() == Error::GcodeSyntax); }
  SECTION("N not first") { CHECK(program_error("G1 N10 X1").code() == Error::GcodeSyntax); }
  SECTION("an O-word not first") { CHECK(program_error("G1 o100 call").code() == Error::GcodeSyntax); }
  SECTION("an error in a line that never runs is not raised") {
    CHECK(x_values(run_program("G0 X1\nM2\nG1 X[1/0]\n")) == std::vector<double>{1.0});
  }
}
