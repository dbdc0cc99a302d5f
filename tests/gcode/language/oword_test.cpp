// SPDX-License-Identifier: MIT
// O-words: if/elseif/else, while, do-while, repeat, break, continue, subroutines with arguments,
// locals and return values, LinuxCNC's label rules, and the limits that stop an endless program.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "program_run.hpp"

using namespace curvestep;
using namespace curvestep::host;
using namespace curvestep::host::gcode;
using namespace curvestep::testing;

using Values = std::vector<double>;

TEST_CASE("language: if / elseif / else take exactly one branch", "[gcode][language][oword]") {
  const auto branch = [](int value) {
    return x_values(run_program("#1 = " + std::to_string(value) +
                                "\n"
                                "o10 if [#1 EQ 1]\n"
                                "  G0 X1\n"
                                "o10 elseif [#1 EQ 2]\n"
                                "  G0 X2\n"
                                "o10 elseif [#1 GT 2]\n"
                                "  G0 X3\n"
                                "o10 else\n"
                                "  G0 X4\n"
                                "o10 endif\n"
                                "G0 X9\n"));
  };
  CHECK(branch(1) == Values{1, 9});
  CHECK(branch(2) == Values{2, 9});
  CHECK(branch(5) == Values{3, 9});
  CHECK(branch(0) == Values{4, 9});
  CHECK(x_values(run_program("o1 if [0]\nG0 X1\no1 endif\nG0 X2")) == Values{2});
}

TEST_CASE("language: while runs its body once per pass, the condition is tested first", "[gcode][language][oword]") {
  CHECK(x_values(run_program("#1 = 0\n"
                             "o100 while [#1 LT 4]\n"
                             "  G1 X#1\n"
                             "  #1 = [#1 + 1]\n"
                             "o100 endwhile\n")) == Values{0, 1, 2, 3});
  CHECK(x_values(run_program("o100 while [0]\nG1 X1\no100 endwhile\nG1 X2")) == Values{2});
}

TEST_CASE("language: do ... while runs at least once", "[gcode][language][oword]") {
  CHECK(x_values(run_program("#1 = 10\n"
                             "o<loop> do\n"
                             "  G1 X#1\n"
                             "  #1 = [#1 + 1]\n"
                             "o<loop> while [#1 LT 3]\n")) == Values{10});
  CHECK(x_values(run_program("#1 = 0\n"
                             "o<loop> do\n"
                             "  G1 X#1\n"
                             "  #1 = [#1 + 1]\n"
                             "o<loop> while [#1 LT 3]\n")) == Values{0, 1, 2});
}

TEST_CASE("language: repeat runs its body n times (0 or less: never), nested loops", "[gcode][language][oword]") {
  CHECK(run_program("o1 repeat [3]\nG1 X1\no1 endrepeat\n").size() == 3);
  CHECK(run_program("o1 repeat [0]\nG1 X1\no1 endrepeat\n").empty());
  CHECK(run_program("o1 repeat [-2]\nG1 X1\no1 endrepeat\n").empty());
  CHECK(run_program("o1 repeat [3]\n"
                    "  o2 repeat [4]\n"
                    "    G1 X1\n"
                    "  o2 endrepeat\n"
                    "o1 endrepeat\n")
            .size() == 12);
}

TEST_CASE("language: break leaves the loop, continue starts the next pass", "[gcode][language][oword]") {
  CHECK(x_values(run_program("#1 = 0\n"
                             "o1 while [1]\n"
                             "  #1 = [#1 + 1]\n"
                             "  o2 if [#1 EQ 3]\n"
                             "    o1 continue\n"
                             "  o2 endif\n"
                             "  o3 if [#1 GT 5]\n"
                             "    o1 break\n"
                             "  o3 endif\n"
                             "  G1 X#1\n"
                             "o1 endwhile\n"
                             "G1 X100\n")) == Values{1, 2, 4, 5, 100});
  CHECK(x_values(run_program("#1 = 0\n"
                             "o1 repeat [5]\n"
                             "  #1 = [#1 + 1]\n"
                             "  o2 if [#1 MOD 2 EQ 0]\n"
                             "    o1 continue\n"
                             "  o2 endif\n"
                             "  G1 X#1\n"
                             "o1 endrepeat\n")) == Values{1, 3, 5});
  CHECK(x_values(run_program("#1 = 0\n"
                             "o1 do\n"
                             "  #1 = [#1 + 1]\n"
                             "  o2 if [#1 EQ 2]\n"
                             "    o1 continue\n"
                             "  o2 endif\n"
                             "  G1 X#1\n"
                             "o1 while [#1 LT 4]\n")) == Values{1, 3, 4});
}

TEST_CASE("language: a break leaves an outer loop named by its label", "[gcode][language][oword]") {
  CHECK(x_values(run_program("o1 repeat [3]\n"
                             "  o2 repeat [3]\n"
                             "    G1 X1\n"
                             "    o1 break\n"
                             "  o2 endrepeat\n"
                             "o1 endrepeat\n"
                             "G1 X2\n")) == Values{1, 2});
}

TEST_CASE("language: a subroutine gets its arguments in #1..#30 and restores them on return", "[gcode][language][oword][sub]") {
  const auto blocks = run_program(
      "#1 = 100 #2 = 200 #3 = 300\n"
      "o<move> call [1] [2]\n"
      "G0 X#1 Y#2 Z#3\n"
      "M2\n"
      "o<move> sub\n"
      "  G1 X#1 Y#2 Z#3\n"  // #3 keeps the caller's value (not passed)
      "  #1 = 7\n"
      "o<move> endsub\n");
  REQUIRE(blocks.size() == 3);
  CHECK(word(blocks[0], 'X') == 1.0);
  CHECK(word(blocks[0], 'Y') == 2.0);
  CHECK(word(blocks[0], 'Z') == 300.0);
  CHECK(word(blocks[1], 'X') == 100.0);  // restored after the call
  CHECK(word(blocks[1], 'Y') == 200.0);
  CHECK(word(blocks[1], 'Z') == 300.0);
}

TEST_CASE("language: return and endsub values reach #<_value> and #<_value_returned>", "[gcode][language][oword][sub]") {
  const auto blocks = run_program(
      "o100 sub\n"
      "  o101 if [#1 LT 0]\n"
      "    o100 return [-1]\n"
      "  o101 endif\n"
      "o100 endsub [SQRT[#1]]\n"
      "o200 sub\n"
      "o200 endsub\n"
      "o100 call [16]\n"
      "G1 X#<_value> Y#<_value_returned>\n"
      "o100 call [-3]\n"
      "G1 X#<_value> Y#<_value_returned>\n"
      "o200 call\n"
      "G1 X#<_value> Y#<_value_returned>\n");
  REQUIRE(blocks.size() == 3);
  CHECK(word(blocks[0], 'X') == 4.0);
  CHECK(word(blocks[0], 'Y') == 1.0);
  CHECK(word(blocks[1], 'X') == -1.0);
  CHECK(word(blocks[2], 'X') == 0.0);
  CHECK(word(blocks[2], 'Y') == 0.0);
}

TEST_CASE("language: named locals belong to one call, globals are shared", "[gcode][language][oword][sub]") {
  const auto blocks = run_program(
      "#<n> = 5 #<_g> = 1\n"
      "o<f> sub\n"
      "  G1 X EXISTS[#<n>]\n"  // the caller's local is not visible
      "  #<n> = 9 #<_g> = 2\n"
      "  G1 X#<n>\n"
      "o<f> endsub\n"
      "o<f> call\n"
      "G1 X#<n> Y#<_g>\n");
  REQUIRE(blocks.size() == 3);
  CHECK(word(blocks[0], 'X') == 0.0);
  CHECK(word(blocks[1], 'X') == 9.0);
  CHECK(word(blocks[2], 'X') == 5.0);
  CHECK(word(blocks[2], 'Y') == 2.0);
}

TEST_CASE("language: recursion, computed labels, and the call depth limit", "[gcode][language][oword][sub]") {
  // factorial by recursion: 5! = 120
  const auto blocks = run_program(
      "o<fact> sub\n"
      "  o1 if [#1 LE 1]\n"
      "    o<fact> return [1]\n"
      "  o1 endif\n"
      "  o<fact> call [#1 - 1]\n"
      "o<fact> endsub [#1 * #<_value>]\n"
      "o<fact> call [5]\n"
      "G1 X#<_value>\n"
      "#7 = 300\n"
      "o[#7 - 1] call\n"
      "M2\n"
      "o299 sub\n"
      "  G1 X299\n"
      "o299 endsub\n");
  CHECK(x_values(blocks) == Values{120, 299});
  const LoadError deep = program_error("o1 sub\no1 call\no1 endsub\no1 call\n");
  CHECK(deep.code() == Error::CapacityExceeded);
  CHECK(deep.location().line == 2);
  CHECK(deep.location().field == "o1 call");
  const LoadError missing = program_error("o2 call\n");
  CHECK(missing.code() == Error::GcodeSyntax);
  CHECK(missing.message() ==
        "no subroutine o2 sub in the program, and no file 2.ngc looked for: no subroutine folder given (the program's folder, the "
        "subroutine path)");
}

TEST_CASE("language: label mismatches and misplaced O-words are errors naming the line", "[gcode][language][oword][errors]") {
  SECTION("endif closing another label") {
    const LoadError e = program_error("G0 X1\no100 if [1]\nG0 X2\no101 endif\n");
    CHECK(e.code() == Error::GcodeSyntax);
    CHECK(e.location().line == 4);
    CHECK(e.location().column == 1);
    CHECK(e.location().field == "o101 endif");
    CHECK(e.message() == "o101 endif does not match the open o100 if (line 2, closed by o100 endif): a construct is closed by "
                         "the label that opened it");
  }
  SECTION("endwhile closing an if") { CHECK(program_error("o1 if [1]\no1 endwhile\n").location().line == 2); }
  SECTION("a loop left open") {
    const LoadError e = program_error("o7 while [1]\nG0 X1\n");
    CHECK(e.location().line == 1);
    CHECK(e.message() == "o7 while is not closed: o7 endwhile missing");
  }
  SECTION("else twice") { CHECK(program_error("o1 if [1]\no1 else\no1 else\no1 endif\n").location().line == 3); }
  SECTION("endif without if") { CHECK(program_error("o1 endif\n").message() == "o1 endif without o1 if"); }
  SECTION("break outside its loop") { CHECK(program_error("o1 if [1]\no1 break\no1 endif\n").location().line == 2); }
  SECTION("return outside its sub") { CHECK(program_error("o1 sub\no2 return\no1 endsub\n").location().line == 2); }
  SECTION("a sub inside a sub") { CHECK(program_error("o1 sub\no2 sub\no2 endsub\no1 endsub\n").location().line == 2); }
  SECTION("a sub defined twice") { CHECK(program_error("o1 sub\no1 endsub\no1 sub\no1 endsub\n").location().line == 3); }
  SECTION("words after an O-word") { CHECK(program_error("o1 if [1] G0 X1\no1 endif\n").code() == Error::GcodeSyntax); }
  SECTION("a condition without brackets") { CHECK(program_error("o1 if 1\no1 endif\n").code() == Error::GcodeSyntax); }
  SECTION("an unknown keyword") { CHECK(program_error("o1 loop\n").location().field == "loop"); }
  SECTION("errors in sub bodies are found before the program runs") {
    const LoadError e = program_error("G0 X1\nM2\no9 sub\no9 if [1]\no9 endsub\n");
    CHECK(e.location().line == 5);
  }
  SECTION("an O-word line's syntax error, found before the program runs, names an earlier line's own error too") {
    // Line 2's error is kept until the line runs; line 4's is thrown by the pre-scan. One run shows both
    // (LinuxCNC's `#$name$` parameters, which the flowsnake program uses, are no syntax of ours).
    const std::string program = "G0 X1\n#$a$ = 5\nG0 X2\no1 if [#$a$ GT 1]\no1 endif\nG0 X3 Y=\n";
    const LoadError e = program_error(program);
    CHECK(e.location().line == 4);
    CHECK(e.location().column == 9);  // the `$` after `[#`
    CHECK(e.message() == "a number, #parameter or [expression] expected (before it, test.ngc:2:2: $: a number, #parameter or "
                         "[expression] expected)");
    host::gcode::ProgramOptions skipping;
    skipping.block_delete = true;
    CHECK(program_error("/#$a$ = 5\no1 if [#$a$ GT 1]\no1 endif\n", skipping).message() ==
          "a number, #parameter or [expression] expected");
  }
}

TEST_CASE("language: an endless loop is an error naming the loop, not a hang", "[gcode][language][oword][errors]") {
  SECTION("a small budget") {
    ProgramOptions options;
    options.max_executed_lines = 1000;
    const LoadError e = program_error("G0 X0\no<spin> while [1]\n  #1 = [#1 + 1]\no<spin> endwhile\n", options);
    CHECK(e.code() == Error::IterationLimit);
    CHECK(e.location().file == "test.ngc");
    CHECK(e.location().line == 2);
    CHECK(e.location().field == "o<spin> while");
  }
  SECTION("the default budget of 10 million lines") {
    const LoadError e = program_error("o1 do\no1 while [1]\n");
    CHECK(e.code() == Error::IterationLimit);
    CHECK(e.location().field == "o1 do");
    CHECK(e.message().find("more than 10000000 lines executed") == 0);
  }
}

TEST_CASE("language: a bolt circle of 6 holes from a while loop and a subroutine", "[gcode][language][oword][program]") {
  const auto blocks = run_program(
      "%\n"
      "(bolt circle: 6 holes, radius 20, centre 50 50)\n"
      "G21 G90\n"
      "#<count> = 6\n"
      "#<radius> = 20\n"
      "#<i> = 0\n"
      "o<bolt> while [#<i> LT #<count>]\n"
      "  #<angle> = [360 / #<count> * #<i>]\n"
      "  o<hole> call [50 + #<radius> * COS[#<angle>]] [50 + #<radius> * SIN[#<angle>]] [-3]\n"
      "  #<i> = [#<i> + 1]\n"
      "o<bolt> endwhile\n"
      "M2\n"
      "\n"
      "o<hole> sub (x, y, depth)\n"
      "  G0 X#1 Y#2\n"
      "  G1 Z#3 F100\n"
      "  G0 Z1\n"
      "o<hole> endsub\n"
      "%\n");
  REQUIRE(blocks.size() == 1 + 6 * 3 + 1);
  CHECK(word(blocks[0], 'G') == 21.0);
  const double s = 20.0 * std::sqrt(3.0) / 2.0;  // 20 sin 60°
  const double xs[6] = {70, 60, 40, 30, 40, 60};
  const double ys[6] = {50, 50 + s, 50 + s, 50, 50 - s, 50 - s};
  for (std::size_t hole = 0; hole < 6; ++hole) {
    const auto& rapid = blocks[1 + 3 * hole];
    CHECK(rapid.line == 15);
    CHECK(word(rapid, 'G') == 0.0);
    CHECK(word(rapid, 'X') == Approx(xs[hole]).margin(1e-12));
    CHECK(word(rapid, 'Y') == Approx(ys[hole]).margin(1e-12));
    const auto& plunge = blocks[2 + 3 * hole];
    CHECK(plunge.line == 16);
    CHECK(word(plunge, 'Z') == -3.0);
    CHECK(word(plunge, 'F') == 100.0);
    CHECK(word(blocks[3 + 3 * hole], 'Z') == 1.0);
  }
  CHECK(word(blocks.back(), 'M') == 2.0);
}

TEST_CASE("language: a file longer than max_lines is refused at the first line past the limit", "[gcode][language][limits]") {
  curvestep::host::gcode::ProgramOptions options;
  options.max_lines = 3;
  SECTION("three lines, the last ended by a newline or not, are read") {
    CHECK(run_program("G0 X1\nG0 X2\nG0 X3\n", options).size() == 3);
    CHECK(run_program("G0 X1\nG0 X2\nG0 X3", options).size() == 3);
  }
  SECTION("a fourth line (even an empty one without a newline) is refused") {
    for (const std::string text : {"G0 X1\nG0 X2\nG0 X3\nG0 X4\n", "G0 X1\nG0 X2\nG0 X3\n\n", "G0 X1\nG0 X2\nG0 X3\nG0"}) {
      const LoadError e = program_error(text, options);
      CHECK(e.code() == Error::CapacityExceeded);
      CHECK(e.location().line == 4);
      CHECK(e.location().file == "test.ngc");
      CHECK(e.message() == "the program has more than 3 lines, the most a G-code file may have (docs/robustness.md): split it into several files");
    }
  }
  CHECK(curvestep::host::gcode::default_max_program_lines == 10'000'000);
}
