// SPDX-License-Identifier: MIT
// Fanuc-style numbered programs as LinuxCNC reads them (docs/gcode.md): `O100` on a program's first
// line is its number; elsewhere `O100` ... `M99` is a numbered subprogram of the same file that
// `M98 P100 [L passes]` runs, with #1-#30 global. The X values expected are worked out by hand from
// each program's control flow; the parameter total is the one LinuxCNC's manual gives for its own
// example (o-code.adoc, "Numbered Subprogram Full Example": 5.25).
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "program_run.hpp"

using namespace curvestep;
using namespace curvestep::host;
using namespace curvestep::host::gcode;
using namespace curvestep::testing;
using Catch::Contains;

using Values = std::vector<double>;

TEST_CASE("numbered programs: M98 P runs O100 ... M99 L times and returns after the M98", "[gcode][language][numbered]") {
  const std::string program =
      "%\n"
      "O0001 (a part's name)\n"
      "G0 X1\n"
      "M98 P100 L2\n"
      "G0 X9\n"
      "M98 P0100\n"
      "M30\n"
      "O100 (the subprogram)\n"
      "G0 X5\n"
      "G0 X6\n"
      "M99\n"
      "%\n";
  const auto blocks = run_program(program);
  CHECK(x_values(blocks) == Values{1, 5, 6, 5, 6, 9, 5, 6});
  for (const auto& block : blocks) {  // M98, its P and L, and M99 are the reader's, not the machine's
    CHECK(block.find('P') == nullptr);
    CHECK(block.find('L') == nullptr);
    if (const auto* m = block.find('M')) CHECK(m->value == 30.0);
  }
  // The line's other words run first, then the call; L0 runs nothing.
  CHECK(x_values(run_program("G0 X2 M98 P7\nM98 P7 L0\nG0 X3\nM2\nO7\nG0 X4\nM99\n")) == Values{2, 4, 3});
  // A subprogram may come before its call (LinuxCNC wants it after: docs/gcode.md), and the main
  // program skips a definition it runs into; on the first line, O7 would be the program's number.
  CHECK(x_values(run_program("G0 X0\nO7\nG0 X4\nM99\nG0 X1\nM98 P7\nG0 X2\n")) == Values{0, 1, 4, 2});
  CHECK_THAT(program_error("O7\nG0 X4\nM99\n").what(),
             Contains("test.ngc:3:1") && Contains("endless program") && Contains("the O-word on line 1 is the program's number") &&
                 Contains("run on its own, it ends with M2 or M30"));
}

TEST_CASE("numbered programs: nested calls share #1-#30 (LinuxCNC's example totals 5.25)", "[gcode][language][numbered]") {
  const auto blocks = run_program(
      "O1\n"
      "#1 = 0\n"
      "M98 P100 L5\n"
      "G0 X#1\n"
      "M30\n"
      "O100\n"
      "#1 = [#1 + 1]\n"
      "M98 P200 L5\n"
      "M99\n"
      "O200\n"
      "#1 = [#1 + 0.01]\n"
      "M99\n");
  REQUIRE(x_values(blocks).size() == 1);
  CHECK(x_values(blocks).front() == Approx(5.25).margin(1e-12));
}

TEST_CASE("numbered programs: an M99 inside a construct of the program returns from it", "[gcode][language][numbered]") {
  const std::string program =
      "#2 = 1\nM98 P10\n#2 = 0\nM98 P10\nM30\n"
      "O10\n"
      "o1 if [#2 EQ 1]\n"
      "  G0 X1\n"
      "  M99\n"
      "o1 endif\n"
      "G0 X2\n"
      "M99\n";
  CHECK(x_values(run_program(program)) == Values{1, 2});
}

TEST_CASE("numbered programs: a long subprogram is read from the file by seeks, the return included", "[gcode][language][numbered]") {
  // More lines than the reader keeps parsed: the return to the line after M98 is a seek.
  std::string program = "M98 P1 L2\nG0 X-1\nM30\nO1\n";
  Values expected;
  for (int pass = 0; pass < 2; ++pass) {
    for (int i = 0; i < 400; ++i) expected.push_back(i);
  }
  expected.push_back(-1);
  for (int i = 0; i < 400; ++i) program += "G0 X" + std::to_string(i) + "\n";
  program += "M99\n";
  CHECK(x_values(run_program(program)) == expected);
}

TEST_CASE("numbered programs: errors name the line and what to write instead", "[gcode][language][numbered][errors]") {
  const auto message = [](const std::string& text) { return std::string(program_error(text).what()); };
  // M99 that runs in the main program: LinuxCNC restarts the program forever.
  CHECK_THAT(message("G0 X1\nM99\n"), Contains("test.ngc:2:1") && Contains("endless program") && Contains("M2 or M30") &&
                                         !Contains("program's number"));
  // ... but one after the end never runs.
  CHECK(x_values(run_program("G0 X1\nM30\nM99\n")) == Values{1});
  CHECK_THAT(message("M98 P5\nM30\n"), Contains("test.ngc:1:5") && Contains("no numbered program O5"));
  CHECK_THAT(message("M98\n"), Contains("test.ngc:1:1") && Contains("M98 needs P"));
  CHECK_THAT(message("M98 P1.5\nO1\nM99\n"), Contains("test.ngc:1:5") && Contains("whole number") && Contains("1.5 given"));
  CHECK_THAT(message("M98 P1 L-2\nM30\nO1\nM99\n"), Contains("test.ngc:1:8") && Contains("-2 given"));
  CHECK_THAT(message("M98 P1\nM30\nO1\nM99 P3\n"), Contains("test.ngc:4:5") && Contains("M99 P"));
  // The two styles do not call each other (LinuxCNC).
  CHECK_THAT(message("M98 P3\nM30\no3 sub\no3 endsub\n"), Contains("test.ngc:1:1") && Contains("o3 call"));
  CHECK_THAT(message("o3 call\nM30\nO3\nM99\n"), Contains("test.ngc:1:1") && Contains("M98 P3"));
  // Structure, found before anything runs.
  CHECK_THAT(message("G0 X1\nM30\nO100\nG0 X2\n"), Contains("test.ngc:3:1") && Contains("o100 is not closed: M99 missing"));
  CHECK_THAT(message("M30\no1 sub\nM99\no1 endsub\n"), Contains("test.ngc:3:1") && Contains("M99 inside o1 sub"));
  CHECK_THAT(message("o5 if [1]\nO100\nM99\no5 endif\n"), Contains("test.ngc:2:1") && Contains("cannot be defined inside o5 if"));
  CHECK_THAT(message("M30\nO7\nM99\nO7\nM99\n"), Contains("test.ngc:4:1") && Contains("defined twice (first on line 2)"));
  CHECK_THAT(message("M30\no7 sub\no7 endsub\nO7\nM99\n"), Contains("test.ngc:4:1") && Contains("as a sub and as a numbered program"));
  CHECK_THAT(message("M30\nO7\nO8\nM99\n"), Contains("test.ngc:3:1") && Contains("M99 missing before it"));
  CHECK_THAT(message("O100 G0 X1\n"), Contains("test.ngc:1:6") && Contains("numbered program's O100 alone on its line"));
  CHECK_THAT(message("G0 X1\nM98 P1\nM30\nO1\nM98 P1\nM99\n"), Contains("test.ngc:5:1") && Contains("nested deeper"));
  // A G code that reads P or L beside M98 would take M98's.
  CHECK_THAT(message("G4 M98 P1\nM30\nO1\nM99\n"), Contains("test.ngc:1:1") && Contains("M98 takes the line's P and L"));
  // M98 and M99 are found before the program runs: not computed.
  CHECK_THAT(message("#1 = 98\nM#1 P1\nM30\nO1\nM99\n"), Contains("test.ngc:2:1") && Contains("not computed"));
}

TEST_CASE("numbered programs: P within 0.0001 of a whole number, L rounded (LinuxCNC's rules)", "[gcode][language][numbered]") {
  CHECK(x_values(run_program("M98 P7.00005 L[0.3/0.1]\nM30\nO7\nG0 X4\nM99\n")) == Values{4, 4, 4});
  CHECK(x_values(run_program("M98 P7 L2.4\nM30\nO7\nG0 X4\nM99\n")) == Values{4, 4});
  CHECK_THAT(program_error("M98 P7.001\nM30\nO7\nM99\n").what(), Contains("test.ngc:1:5") && Contains("0..999999999 (7.001 given)"));
}

TEST_CASE("language: a grbl console command is named as one", "[gcode][language][errors]") {
  const auto message = [](const std::string& text) { return std::string(program_error(text).what()); };
  CHECK_THAT(message("$H\nG0 X1\n"), Contains("test.ngc:1:1") && Contains("$H") && Contains("grbl console command"));
  CHECK_THAT(message("G0 X1\n?\n"), Contains("test.ngc:2:1") && Contains("grbl console command"));
  // Elsewhere on a line, '$' is an unexpected character as before.
  CHECK_THAT(message("G0 X1 $\n"), Contains("test.ngc:1:7") && Contains("a word starts with a letter"));
}
