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

/// The value of `letter` in a block, or -1 if it has none.
double value_of(const ProgramBlock& block, char letter) {
  const ProgramWord* w = block.find(letter);
  return w == nullptr ? -1.0 : w->value;
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
  REQUIRE(blocks.size() == 4);
  CHECK(blocks[0].line == 1);
  CHECK(blocks[0].file.empty());
  CHECK(value_of(blocks[0], 'X') == 1.0);
  CHECK(blocks[1].line == 3);
  CHECK(blocks[1].file == scratch.path("square_x.ngc"));
  CHECK(blocks[1].program_line == 2);
  CHECK(blocks[1].source == "  G1 X[#1*2]");
  CHECK(value_of(blocks[1], 'X') == 10.0);
  CHECK(blocks[2].line == 3);
  CHECK(blocks[2].file.empty());
  CHECK(blocks[2].program_line == 3);
  CHECK(value_of(blocks[2], 'X') == 25.0);
  CHECK(value_of(blocks[2], 'Y') == 1.0);
  CHECK(blocks[3].line == 4);
  CHECK(value_of(blocks[3], 'M') == 2.0);
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
  SECTION("a program file: its folder, then a, then b") {
    const auto blocks = run_file(program, options);
    REQUIRE(blocks.size() == 4);
    CHECK(value_of(blocks[0], 'X') == 1.0);  // where.ngc beside the program
    CHECK(value_of(blocks[1], 'Y') == 5.0);  // a/order.ngc before b/order.ngc
    CHECK(value_of(blocks[2], 'Z') == 3.0);  // only in b
  }
  SECTION("a program given as text has no folder: a, then b") {
    const auto blocks = run_program(text, options);
    REQUIRE(blocks.size() == 4);
    CHECK(value_of(blocks[0], 'X') == 2.0);
    CHECK(value_of(blocks[1], 'Y') == 5.0);
    CHECK(value_of(blocks[2], 'Z') == 3.0);
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
  const auto blocks = run_file(program, options);
  REQUIRE(blocks.size() == 5);
  CHECK(blocks[0].file == scratch.path("lib/outer.ngc"));
  CHECK(blocks[0].line == 2);
  CHECK(blocks[0].program_line == 3);
  CHECK(value_of(blocks[0], 'X') == 2.0);
  CHECK(value_of(blocks[0], 'Y') == 3.0);
  CHECK(value_of(blocks[0], 'Z') == 40.0);
  CHECK(blocks[1].file == scratch.path("lib/inner.ngc"));
  CHECK(blocks[1].line == 3);
  CHECK(blocks[1].program_line == 3);
  CHECK(value_of(blocks[1], 'Z') == 5.0);
  CHECK(blocks[2].file == scratch.path("lib/outer.ngc"));
  CHECK(blocks[2].line == 4);
  CHECK(value_of(blocks[2], 'X') == 50.0);
  CHECK(value_of(blocks[2], 'Y') == 2.0);
  CHECK(blocks[3].file.empty());
  CHECK(blocks[3].line == 4);
  CHECK(value_of(blocks[3], 'X') == 7.0);
  CHECK(value_of(blocks[3], 'Y') == 51.0);
  CHECK(value_of(blocks[3], 'Z') == 40.0);
  CHECK(value_of(blocks[4], 'M') == 2.0);
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
  const auto blocks = run_file(program);
  REQUIRE(blocks.size() == 5);
  CHECK(value_of(blocks[0], 'Z') == 0.0);
  CHECK(value_of(blocks[1], 'Z') == 1.0);
  CHECK(value_of(blocks[2], 'Z') == 2.0);
  CHECK(blocks[2].line == 2);
  CHECK(blocks[2].program_line == 3);
  CHECK(value_of(blocks[3], 'X') == 3.0);
  CHECK(value_of(blocks[3], 'Y') == 120.0);
}

TEST_CASE("subroutine files: a numbered call reads its number's file, as LinuxCNC documents (o123 call)",
          "[gcode][language][oword][subfile]") {
  const ScratchFolder scratch("subfile_numbered");
  const auto program = scratch.write("prog.ngc", "o100 call [4]\no[50*2] call [6]\nM2\n");
  scratch.write("100.ngc", "o100 sub\n  G1 X#1\no100 endsub\nM2\n");
  const auto blocks = run_file(program);
  REQUIRE(blocks.size() == 3);
  CHECK(value_of(blocks[0], 'X') == 4.0);
  CHECK(blocks[0].file == scratch.path("100.ngc"));
  CHECK(value_of(blocks[1], 'X') == 6.0);
  CHECK(blocks[1].program_line == 2);
}

TEST_CASE("subroutine files: a file that is missing, names another sub, has no endsub, a second sub or cannot be read is an error",
          "[gcode][language][oword][subfile][errors]") {
  const ScratchFolder scratch("subfile_errors");
  const std::string root = scratch.root().string();
  scratch.folder("lib");
  ProgramOptions options;
  options.subroutine_path = {scratch.root() / "lib"};
  SECTION("no file in any folder: the error at the call lists the folders searched") {
    const auto program = scratch.write("prog.ngc", "G0 X1\no<missing> call\nM2\n");
    const LoadError e = file_error(program, options);
    CHECK(e.code() == Error::GcodeSyntax);
    CHECK(e.location().file == "prog.ngc");
    CHECK(e.location().line == 2);
    CHECK(e.location().column == 1);
    CHECK(e.location().field == "o<missing> call");
    CHECK(e.message() == "no subroutine o<missing> sub in the program, and no file missing.ngc in " + root + ", " + scratch.path("lib") +
                             " (the folders searched, in this order)");
  }
  SECTION("a name no file may have") {
    const auto program = scratch.write("dotted.ngc", "o<a.b> call\n");
    const LoadError e = file_error(program, options);
    CHECK(e.location().line == 1);
    CHECK(e.message() ==
          "no subroutine o<a.b> sub in the program, and no file can hold it: a subroutine file's name has lower-case letters, digits, "
          "'-' and '_' only (LinuxCNC)");
  }
  SECTION("the file's sub has another name: the error names that sub's line in the file") {
    const auto program = scratch.write("prog.ngc", "G0 X1\no<wrong> call\n");
    scratch.write("lib/wrong.ngc", "(wrong.ngc)\no<other> sub\n  G1 X1\no<other> endsub\n");
    const LoadError e = file_error(program, options);
    CHECK(e.code() == Error::GcodeSyntax);
    CHECK(e.location().file == scratch.path("lib/wrong.ngc"));
    CHECK(e.location().line == 2);
    CHECK(e.location().field == "o<other> sub");
    CHECK(e.message() == "the subroutine file of o<wrong> defines o<other> instead: the sub in wrong.ngc must be o<wrong>");
  }
  SECTION("a file without its sub") {
    const auto program = scratch.write("prog.ngc", "o<empty> call\n");
    scratch.write("lib/empty.ngc", "G1 X1\nM2\n");
    const LoadError e = file_error(program, options);
    CHECK(e.location().file == scratch.path("lib/empty.ngc"));
    CHECK(e.location().line == 0);
    CHECK(e.message() == "no o<empty> sub in this subroutine file (called as o<empty> call): the file must define it");
  }
  SECTION("no endsub: the error names the sub's line in the file") {
    const auto program = scratch.write("prog.ngc", "G0 X1\no<noend> call\n");
    scratch.write("lib/noend.ngc", "o<noend> sub\n  G1 X1\nM2\n");
    const LoadError e = file_error(program, options);
    CHECK(e.code() == Error::GcodeSyntax);
    CHECK(e.location().file == scratch.path("lib/noend.ngc"));
    CHECK(e.location().line == 1);
    CHECK(e.location().column == 1);
    CHECK(e.location().field == "o<noend> sub");
    CHECK(e.message() == "o<noend> sub is not closed: o<noend> endsub missing");
  }
  SECTION("a second sub in the file") {
    const auto program = scratch.write("prog.ngc", "o<two> call\n");
    scratch.write("lib/two.ngc", "o<two> sub\no<two> endsub\no<three> sub\no<three> endsub\n");
    const LoadError e = file_error(program, options);
    CHECK(e.location().file == scratch.path("lib/two.ngc"));
    CHECK(e.location().line == 3);
    CHECK(e.location().field == "o<three> sub");
    CHECK(e.message() == "a second subroutine in the file of o<two>: a subroutine file holds one sub (LinuxCNC)");
  }
  SECTION("a name found that is not a readable file: the error at the call") {
    const auto program = scratch.write("prog.ngc", "G0 X1\n\no<dir> call\n");
    scratch.folder("lib/dir.ngc");
    const LoadError e = file_error(program, options);
    CHECK(e.code() == Error::GcodeSyntax);
    CHECK(e.location().file == "prog.ngc");
    CHECK(e.location().line == 3);
    CHECK(e.location().field == "o<dir> call");
    CHECK(e.message() == "the subroutine file " + scratch.path("lib/dir.ngc") + " of o<dir> cannot be read: it is not a regular file");
  }
  SECTION("an error in a line of the file names the file and its line") {
    const auto program = scratch.write("prog.ngc", "G0 X1\no<bad> call\n");
    scratch.write("lib/bad.ngc", "o<bad> sub\n  G1 X1\n  G1 X[2/0]\no<bad> endsub\n");
    const LoadError e = file_error(program, options);
    CHECK(e.code() == Error::DivisionByZero);
    CHECK(std::string(e.what()) == scratch.path("lib/bad.ngc") + ":3:7: [2/0]: division by zero");
  }
}
