// SPDX-License-Identifier: MIT
// Subroutine files (LinuxCNC's "Calling Files", SUBROUTINE_PATH): a call to a sub the program does
// not define reads name.ngc from the program's folder, then from each folder of the subroutine
// path in order, and runs its sub as if it were in the program. The values expected are worked out
// by hand from each program and file; the errors name the sub file and its line, or the call.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "../scratch_folder.hpp"
#include "program_run.hpp"

using namespace curvestep;
using namespace curvestep::host;
using namespace curvestep::host::gcode;
using namespace curvestep::testing;

namespace {

std::vector<ProgramBlock> run_file(const std::filesystem::path& path, ProgramOptions options = {}) {
  ProgramReader reader = ProgramReader::open_file(path, "prog.ngc", std::move(options));
  std::vector<ProgramBlock> blocks;
  while (auto block = reader.next()) blocks.push_back(std::move(*block));
  return blocks;
}

LoadError file_error(const std::filesystem::path& path, ProgramOptions options = {}) {
  try {
    (void)run_file(path, std::move(options));
  } catch (const LoadError& error) {
    return error;
  }
  FAIL("no error for " << path);
  return LoadError({}, "", Error::GcodeSyntax);
}

/// What a block must hold: its file (empty: the program's own), its line there, the program's line
/// (the call's, in a subroutine file) and the values of some of its words.
struct ExpectedBlock {
  std::string file;
  std::size_t line;
  std::size_t program_line;
  std::vector<std::pair<char, double>> words;
};

void check_blocks(const std::vector<ProgramBlock>& blocks, const std::vector<ExpectedBlock>& expected) {
  REQUIRE(blocks.size() == expected.size());
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    INFO("block " << i << ": " << blocks[i].source);
    CHECK(blocks[i].file == expected[i].file);
    CHECK(blocks[i].line == expected[i].line);
    CHECK(blocks[i].program_line == expected[i].program_line);
    for (const auto& [letter, value] : expected[i].words) {
      INFO(letter);
      const ProgramWord* w = blocks[i].find(letter);
      REQUIRE(w != nullptr);
      CHECK(w->value == value);
    }
  }
}

}  // namespace

TEST_CASE("subroutine files: o<name> call runs name.ngc from the program's folder, lower-cased, with its argument and return value",
          "[gcode][language][oword][subfile]") {
  const ScratchFolder scratch("subfile_program_folder");
  const auto program = scratch.write("prog.ngc",
                                     "G0 X1\n"
                                     "o<Square_X> call [5]\n"
                                     "G0 X#<_value> Y#<_value_returned>\n"
                                     "M2\n");
  scratch.write("square_x.ngc",
                "(a subroutine file: its name is the sub's, lower case)\n"
                "o<square_x> sub\n"
                "  G1 X[#1*2]\n"
                "o<square_x> endsub [#1*#1]\n"
                "M2\n");
  // #1 = 5: the sub's line 3 moves to X10 and returns 25, which the program reads with _value_returned 1.
  // The M2 after endsub never runs: the program's own M2 (its line 4) ends it.
  const auto blocks = run_file(program);
  check_blocks(blocks, {{"", 1, 1, {{'X', 1}}},
                        {scratch.path("square_x.ngc"), 3, 2, {{'X', 10}}},
                        {"", 3, 3, {{'X', 25}, {'Y', 1}}},
                        {"", 4, 4, {{'M', 2}}}});
  CHECK(blocks[1].source == "  G1 X[#1*2]");
}

TEST_CASE("subroutine files: the program's folder is searched first, then the subroutine path in its order",
          "[gcode][language][oword][subfile]") {
  const ScratchFolder scratch("subfile_search_order");
  const std::string text =
      "o<where> call\n"
      "G0 X#<_value>\n"
      "o<order> call\n"
      "G0 Y#<_value>\n"
      "o<only_in_b> call\n"
      "G0 Z#<_value>\n"
      "M2\n";
  const auto program = scratch.write("prog.ngc", text);
  scratch.write("where.ngc", "o<where> sub\no<where> endsub [1]\n");
  scratch.write("a/where.ngc", "o<where> sub\no<where> endsub [2]\n");
  scratch.write("b/where.ngc", "o<where> sub\no<where> endsub [4]\n");
  scratch.write("a/order.ngc", "o<order> sub\no<order> endsub [5]\n");
  scratch.write("b/order.ngc", "o<order> sub\no<order> endsub [6]\n");
  scratch.write("b/only_in_b.ngc", "o<only_in_b> sub\no<only_in_b> endsub [3]\n");
  ProgramOptions options;
  options.subroutine_path = {scratch.root() / "a", scratch.root() / "b"};
  // where.ngc beside the program (1) before a's (2); a/order.ngc (5) before b's (6); only_in_b from b (3).
  SECTION("a program file: its folder, then a, then b") {
    check_blocks(run_file(program, options), {{"", 2, 2, {{'X', 1}}}, {"", 4, 4, {{'Y', 5}}}, {"", 6, 6, {{'Z', 3}}}, {"", 7, 7, {}}});
  }
  SECTION("a program given as text has no folder: a, then b") {
    check_blocks(run_program(text, options), {{"", 2, 2, {{'X', 2}}}, {"", 4, 4, {{'Y', 5}}}, {"", 6, 6, {{'Z', 3}}}, {"", 7, 7, {}}});
  }
}

TEST_CASE("subroutine files: a file sub calls another file's sub, #1-#30 are passed and restored, values come back",
          "[gcode][language][oword][subfile]") {
  const ScratchFolder scratch("subfile_nested");
  const auto program = scratch.write("prog.ngc",
                                     "#1 = 7\n"
                                     "#4 = 40\n"
                                     "o<outer> call [2] [3]\n"
                                     "G0 X#1 Y#<_value> Z#4\n"
                                     "M2\n");
  scratch.write("lib/outer.ngc",
                "o<outer> sub\n"
                "  G1 X#1 Y#2 Z#4\n"
                "  o<inner> call [#1+#2]\n"
                "  G1 X#<_value> Y#1\n"
                "o<outer> endsub [#<_value>+1]\n");
  scratch.write("lib/inner.ngc",
                "o<inner> sub\n"
                "  #4 = 99\n"
                "  G1 Z#1\n"
                "o<inner> endsub [#1*10]\n"
                "M2\n");
  ProgramOptions options;
  options.subroutine_path = {scratch.root() / "lib"};
  // outer: #1 = 2, #2 = 3, #4 keeps the caller's 40 -> X2 Y3 Z40; inner: #1 = 2 + 3 = 5 -> Z5, returns
  // 50; outer, its #1 back to 2 -> X50 Y2, returns 51; the program, its #1 back to 7 and #4 to 40
  // (inner's #4 = 99 is undone by both returns) -> X7 Y51 Z40.
  const std::string outer = scratch.path("lib/outer.ngc");
  check_blocks(run_file(program, options), {{outer, 2, 3, {{'X', 2}, {'Y', 3}, {'Z', 40}}},
                                            {scratch.path("lib/inner.ngc"), 3, 3, {{'Z', 5}}},
                                            {outer, 4, 3, {{'X', 50}, {'Y', 2}}},
                                            {"", 4, 4, {{'X', 7}, {'Y', 51}, {'Z', 40}}},
                                            {"", 5, 5, {{'M', 2}}}});
}

TEST_CASE("subroutine files: a file sub runs again from a loop, recurses with return, and keeps its own labels",
          "[gcode][language][oword][subfile]") {
  const ScratchFolder scratch("subfile_loops");
  const auto program = scratch.write("prog.ngc",
                                     "#100 = 0\n"
                                     "o1 repeat [3]\n"
                                     "  o<count> call [#100]\n"
                                     "  #100 = #<_value>\n"
                                     "o1 endrepeat\n"
                                     "o<fact> call [5]\n"
                                     "G0 X#100 Y#<_value>\n"
                                     "M2\n");
  scratch.write("count.ngc", "o<count> sub\n  G1 Z#1\no<count> endsub [#1+1]\n");
  // o1 here is an if, the program's o1 a repeat: each file has its labels.
  scratch.write("fact.ngc",
                "o<fact> sub\n"
                "  o1 if [#1 LE 1]\n"
                "    o<fact> return [1]\n"
                "  o1 endif\n"
                "  o<fact> call [#1-1]\n"
                "o<fact> endsub [#1*#<_value>]\n");
  // count returns 1, 2, 3 (Z0, Z1, Z2); 5! = 120.
  const std::string count = scratch.path("count.ngc");
  check_blocks(run_file(program), {{count, 2, 3, {{'Z', 0}}},
                                   {count, 2, 3, {{'Z', 1}}},
                                   {count, 2, 3, {{'Z', 2}}},
                                   {"", 7, 7, {{'X', 3}, {'Y', 120}}},
                                   {"", 8, 8, {{'M', 2}}}});
}

TEST_CASE("subroutine files: a numbered call reads its number's file, as LinuxCNC documents (o123 call)",
          "[gcode][language][oword][subfile]") {
  const ScratchFolder scratch("subfile_numbered");
  const auto program = scratch.write("prog.ngc", "o100 call [4]\no[50*2] call [6]\nM2\n");
  scratch.write("100.ngc", "o100 sub\n  G1 X#1\no100 endsub\nM2\n");
  const std::string file = scratch.path("100.ngc");
  check_blocks(run_file(program), {{file, 2, 1, {{'X', 4}}}, {file, 2, 2, {{'X', 6}}}, {"", 3, 3, {{'M', 2}}}});
}

namespace {

/// What an error must say: where (file, line, field as LoadError's location) and why.
struct ExpectedError {
  std::string file;
  std::size_t line;
  std::string field;
  std::string message;
  Error code = Error::GcodeSyntax;
};

void check_error(const LoadError& e, const ExpectedError& expected) {
  CHECK(e.code() == expected.code);
  CHECK(e.location().file == expected.file);
  CHECK(e.location().line == expected.line);
  CHECK(e.location().field == expected.field);
  CHECK(e.message() == expected.message);
}

}  // namespace

TEST_CASE("subroutine files: a call whose file is missing, has a name no file may have or is not a readable file is an error at the call",
          "[gcode][language][oword][subfile][errors]") {
  const ScratchFolder scratch("subfile_call_errors");
  ProgramOptions options;
  options.subroutine_path = {scratch.folder("lib")};
  scratch.folder("lib/dir.ngc");
  const auto program = scratch.write("prog.ngc", "G0 X1\no<missing> call\no<a.b> call\no<dir> call\nM2\n");
  // Each call in turn: the program's line 2 with missing.ngc nowhere, then (missing.ngc written)
  // line 3, then (a.b left out) line 4.
  check_error(file_error(program, options),
              {"prog.ngc", 2, "o<missing> call",
               "no subroutine o<missing> sub in the program, and no file missing.ngc in " + scratch.root().string() + ", " +
                   scratch.path("lib") + " (the folders searched, in this order)"});
  scratch.write("lib/missing.ngc", "o<missing> sub\no<missing> endsub\n");
  check_error(file_error(program, options),
              {"prog.ngc", 3, "o<a.b> call",
               "no subroutine o<a.b> sub in the program, and no file can hold it: a subroutine file's name has lower-case letters, "
               "digits, '-' and '_' only (LinuxCNC)"});
  scratch.write("prog.ngc", "G0 X1\no<missing> call\n\no<dir> call\nM2\n");
  check_error(file_error(program, options),
              {"prog.ngc", 4, "o<dir> call",
               "the subroutine file " + scratch.path("lib/dir.ngc") + " of o<dir> cannot be read: it is not a regular file"});
}

TEST_CASE("subroutine files: a file whose sub has another name, that has no sub, no endsub or a second sub is an error in the file",
          "[gcode][language][oword][subfile][errors]") {
  const ScratchFolder scratch("subfile_file_errors");
  ProgramOptions options;
  options.subroutine_path = {scratch.folder("lib")};
  struct Case {
    std::string name;  ///< called as o<name>, read from lib/name.ngc
    std::string text;
    std::size_t line;
    std::string field;
    std::string message;
    Error code = Error::GcodeSyntax;
  };
  const std::vector<Case> cases = {
      {"wrong", "(wrong.ngc)\no<other> sub\n  G1 X1\no<other> endsub\n", 2, "o<other> sub",
       "the subroutine file of o<wrong> defines o<other> instead: the sub in wrong.ngc must be o<wrong>"},
      {"empty", "G1 X1\nM2\n", 0, "", "no o<empty> sub in this subroutine file (called as o<empty> call): the file must define it"},
      {"noend", "o<noend> sub\n  G1 X1\nM2\n", 1, "o<noend> sub", "o<noend> sub is not closed: o<noend> endsub missing"},
      {"two", "o<two> sub\no<two> endsub\no<three> sub\no<three> endsub\n", 3, "o<three> sub",
       "a second subroutine in the file of o<two>: a subroutine file holds one sub (LinuxCNC)"},
      // An error raised when a line of the file runs names it as the program's would be named.
      {"bad", "o<bad> sub\n  G1 X1\n  G1 X[2/0]\no<bad> endsub\n", 3, "[2/0]", "division by zero", Error::DivisionByZero},
  };
  for (const auto& c : cases) {
    INFO(c.name);
    const auto program = scratch.write("prog.ngc", "G0 X1\no<" + c.name + "> call\n");
    scratch.write("lib/" + c.name + ".ngc", c.text);
    check_error(file_error(program, options), {scratch.path("lib/" + c.name + ".ngc"), c.line, c.field, c.message, c.code});
  }
}
