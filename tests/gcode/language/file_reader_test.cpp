// SPDX-License-Identifier: MIT
// A program read from a file (ProgramReader::open_file) is read as a stream: once for its
// structure, then line by line with a seek for each jump. It must hand out the blocks the text
// reader hands out, with the same errors; the X values expected are worked out by hand from each
// program's control flow.
#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>
#include <unistd.h>
#include <vector>

#include "program_run.hpp"

using namespace curvestep;
using namespace curvestep::host;
using namespace curvestep::host::gcode;
using namespace curvestep::testing;

using Values = std::vector<double>;

namespace {

/// A scratch file holding `text` byte for byte, removed with the object.
class ScratchProgram {
 public:
  ScratchProgram(const std::string& name, const std::string& text)
      : path_("file_reader_" + std::to_string(::getpid()) + "_" + name + ".ngc") {
    std::ofstream out(path_, std::ios::binary);
    out << text;
  }
  ~ScratchProgram() { std::remove(path_.c_str()); }
  ScratchProgram(const ScratchProgram&) = delete;
  ScratchProgram& operator=(const ScratchProgram&) = delete;
  [[nodiscard]] const std::string& path() const { return path_; }

 private:
  std::string path_;
};

std::vector<ProgramBlock> run_file(const std::string& path, ProgramOptions options = {}) {
  ProgramReader reader = ProgramReader::open_file(path, "test.ngc", options);
  std::vector<ProgramBlock> blocks;
  while (auto block = reader.next()) blocks.push_back(std::move(*block));
  return blocks;
}

LoadError file_error(const std::string& path, ProgramOptions options = {}) {
  try {
    (void)run_file(path, options);
  } catch (const LoadError& error) {
    return error;
  }
  FAIL("no error for " << path);
  return LoadError({}, "", Error::GcodeSyntax);
}

/// Every field of two block lists is equal.
void check_same_blocks(const std::vector<ProgramBlock>& from_file, const std::vector<ProgramBlock>& from_text) {
  REQUIRE(from_file.size() == from_text.size());
  for (std::size_t i = 0; i < from_file.size(); ++i) {
    INFO("block " << i);
    CHECK(from_file[i].line == from_text[i].line);
    CHECK(from_file[i].source == from_text[i].source);
    CHECK(from_file[i].block_delete == from_text[i].block_delete);
    REQUIRE(from_file[i].words.size() == from_text[i].words.size());
    for (std::size_t w = 0; w < from_file[i].words.size(); ++w) {
      CHECK(from_file[i].words[w].letter == from_text[i].words[w].letter);
      CHECK(from_file[i].words[w].value == from_text[i].words[w].value);
      CHECK(from_file[i].words[w].column == from_text[i].words[w].column);
    }
    REQUIRE(from_file[i].messages.size() == from_text[i].messages.size());
    for (std::size_t m = 0; m < from_file[i].messages.size(); ++m) CHECK(from_file[i].messages[m].text == from_text[i].messages[m].text);
  }
}

/// The X values of `text` read from a file, after checking the blocks are those of the text reader.
Values file_x_values(const std::string& name, const std::string& text) {
  const ScratchProgram file(name, text);
  const auto blocks = run_file(file.path());
  check_same_blocks(blocks, run_program(text));
  return x_values(blocks);
}

}  // namespace

TEST_CASE("file reader: loops, calls, branches and repeats give the blocks of the text reader", "[gcode][language][file]") {
  SECTION("a while loop") {
    CHECK(file_x_values("while", "#1 = 0\no1 while [#1 LT 3]\n  G0 X#1\n  #1 = [#1 + 1]\no1 endwhile\nG0 X9\n") == Values{0, 1, 2, 9});
  }
  SECTION("calls of a subroutine defined below the main program, with a return value") {
    CHECK(file_x_values("call",
                        "o<twice> call [2]\n"
                        "G0 X#<_value>\n"
                        "o<twice> call [5]\n"
                        "G0 X#<_value>\n"
                        "M2\n"
                        "o<twice> sub\n"
                        "  G0 X#1\n"
                        "  o<twice> return [#1 * 2]\n"
                        "o<twice> endsub\n") == Values{2, 4, 5, 10});
  }
  SECTION("if / elseif / else") {
    const std::string branches =
        "o10 if [#1 EQ 1]\n  G0 X1\no10 elseif [#1 EQ 2]\n  G0 X2\no10 else\n  G0 X4\no10 endif\nG0 X9\n";
    CHECK(file_x_values("if1", "#1 = 1\n" + branches) == Values{1, 9});
    CHECK(file_x_values("if2", "#1 = 2\n" + branches) == Values{2, 9});
    CHECK(file_x_values("if3", "#1 = 7\n" + branches) == Values{4, 9});
  }
  SECTION("an if with 300 elseifs, more lines than the reader keeps parsed, in a loop") {
    std::string program = "#2 = 0\no9 repeat [2]\n#1 = [298 + #2]\no1 if [#1 EQ 0]\n  G0 X0\n";
    for (int k = 1; k <= 300; ++k) program += "o1 elseif [#1 EQ " + std::to_string(k) + "]\n  G0 X" + std::to_string(k) + "\n";
    program += "o1 else\n  G0 X-1\no1 endif\n#2 = 2\no9 endrepeat\n";
    CHECK(file_x_values("elseifs", program) == Values{298, 300});
  }
  SECTION("do / while runs its body once before the test") {
    CHECK(file_x_values("do", "#1 = 5\no2 do\n  G0 X#1\n  #1 = [#1 + 1]\no2 while [#1 LT 3]\nG0 X9\n") == Values{5, 9});
  }
  SECTION("nested repeats") {
    CHECK(file_x_values("repeat", "o1 repeat [2]\n  G0 X1\n  o2 repeat [3]\n    G0 X2\n  o2 endrepeat\no1 endrepeat\n") ==
          Values{1, 2, 2, 2, 1, 2, 2, 2});
  }
  SECTION("break and continue") {
    CHECK(file_x_values("break",
                        "#1 = 0\n"
                        "o1 while [1]\n"
                        "  #1 = [#1 + 1]\n"
                        "  o2 if [#1 EQ 2]\n"
                        "    o1 continue\n"
                        "  o2 endif\n"
                        "  o3 if [#1 GT 4]\n"
                        "    o1 break\n"
                        "  o3 endif\n"
                        "  G0 X#1\n"
                        "o1 endwhile\n"
                        "G0 X9\n") == Values{1, 3, 4, 9});
  }
  SECTION("a program between '%' lines: nothing after the closing one is read") {
    CHECK(file_x_values("percent", "\n%\nG0 X1\no1 repeat [2]\nG0 X2\no1 endrepeat\n%\nG0 X3\no7 endif\n") == Values{1, 2, 2});
  }
  SECTION("CRLF lines, jumped to and read in order") {
    CHECK(file_x_values("crlf", "G0 X1\r\no1 repeat [2]\r\n  G0 X2 (pass)\r\no1 endrepeat\r\nG0 X3\r\n") == Values{1, 2, 2, 3});
    const ScratchProgram file("crlf_source", "G0 X1\r\nG0 X2\r\n");
    const auto blocks = run_file(file.path());
    REQUIRE(blocks.size() == 2);
    CHECK(blocks[1].source == "G0 X2");
  }
  SECTION("a last line without a newline, in a loop and after it") {
    CHECK(file_x_values("last_in_loop", "o1 repeat [2]\nG0 X1\no1 endrepeat") == Values{1, 1});
    CHECK(file_x_values("last", "o1 repeat [2]\nG0 X1\no1 endrepeat\nG0 X2") == Values{1, 1, 2});
  }
  SECTION("a loop body longer than the file reader's 64 KiB window") {
    std::string body;
    for (int i = 0; i < 2000; ++i) body += "(a comment line of about forty-eight bytes, " + std::to_string(i) + ")\n";
    REQUIRE(body.size() > 64 * 1024);  // a jump back goes further than the window holds
    CHECK(file_x_values("long_body", "#1 = 0\no1 repeat [3]\n  #1 = [#1 + 1]\n" + body + "  G0 X#1\n" + body + "o1 endrepeat\nG0 X9\n") ==
          Values{1, 2, 3, 9});
  }
}

TEST_CASE("file reader: errors name the file's line and column as the text reader's do", "[gcode][language][file][errors]") {
  SECTION("an endless loop names the loop") {
    ProgramOptions options;
    options.max_executed_lines = 1000;
    const ScratchProgram file("endless", "G0 X0\no<spin> while [1]\n  #1 = [#1 + 1]\no<spin> endwhile\n");
    const LoadError e = file_error(file.path(), options);
    CHECK(e.code() == Error::IterationLimit);
    CHECK(e.location().file == "test.ngc");
    CHECK(e.location().line == 2);
    CHECK(e.location().field == "o<spin> while");
    CHECK(e.message() == "more than 1000 lines executed: an endless loop? (the limit keeps a program from running forever)");
  }
  SECTION("an endless do loop, stopped on a line after an inner construct, names the do") {
    ProgramOptions options;
    options.max_executed_lines = 1001;  // do, then 3 lines a pass (the false if goes past its endif): the 1002nd is `G0 X1`
    const ScratchProgram file("endless_do", "o1 do\n  o2 if [0]\n  o2 endif\n  G0 X1\no1 while [1]\n");
    const LoadError e = file_error(file.path(), options);
    CHECK(e.code() == Error::IterationLimit);
    CHECK(e.location().line == 1);
    CHECK(e.location().field == "o1 do");
  }
  SECTION("an O-word construct closed by another label") {
    const ScratchProgram file("mismatch", "G0 X1\no1 while [1]\nG0 X2\no2 endwhile\n");
    const LoadError e = file_error(file.path());
    CHECK(e.code() == Error::GcodeSyntax);
    CHECK(e.location().line == 4);
    CHECK(e.location().column == 1);
    CHECK(e.location().field == "o2 endwhile");
  }
  SECTION("an O-word line's syntax error is reported before an earlier structure error, as the text reader does") {
    const std::string text = "o1 endwhile\nG0 X1\no2 bogus [1]\n";
    const ScratchProgram file("syntax_first", text);
    for (const LoadError& e : {file_error(file.path()), program_error(text)}) {
      CHECK(e.code() == Error::GcodeSyntax);
      CHECK(e.location().line == 3);
    }
    const ScratchProgram structure_only("structure_only", "o1 endwhile\nG0 X1\n");
    const LoadError e = file_error(structure_only.path());
    CHECK(e.location().line == 1);
    CHECK(e.location().field == "o1 endwhile");
  }
  SECTION("a construct left open names its first line") {
    const ScratchProgram file("open", "G0 X1\n  o<outer> repeat [2]\nG0 X2\n");
    const LoadError e = file_error(file.path());
    CHECK(e.code() == Error::GcodeSyntax);
    CHECK(e.location().line == 2);
    CHECK(e.location().column == 3);
    CHECK(e.location().field == "o<outer> repeat");
    CHECK(e.message() == "o<outer> repeat is not closed: o<outer> endrepeat missing");
  }
  SECTION("a file longer than max_lines, even with a syntax error before the limit") {
    ProgramOptions options;
    options.max_lines = 3;
    const ScratchProgram file("long", "o1 bogus\nG0 X2\r\nG0 X3\r\n\r\n");
    const LoadError e = file_error(file.path(), options);
    CHECK(e.code() == Error::CapacityExceeded);
    CHECK(e.location().line == 4);
    const ScratchProgram three("three", "G0 X1\nG0 X2\nG0 X3\n");
    CHECK(run_file(three.path(), options).size() == 3);
  }
  SECTION("a file cut short after the pre-scan read it") {
    const ScratchProgram file("cut", "G0 X1\nG0 X2\nG0 X3\n");
    ProgramReader reader = ProgramReader::open_file(file.path(), "test.ngc");
    std::ofstream(file.path(), std::ios::binary | std::ios::trunc) << "G0 X1\n";
    REQUIRE(reader.next());
    CHECK_THROWS_WITH(reader.next(), Catch::Contains("line 3 is past the end of the file: did the file change"));
  }
  SECTION("a file that cannot be opened") {
    CHECK_THROWS_WITH(ProgramReader::open_file("no_such_dir/none.ngc", "none.ngc"), "no_such_dir/none.ngc: cannot open the file");
  }
}

TEST_CASE("file reader: the lines of the file are counted as the text reader counts them", "[gcode][language][file]") {
  const auto count = [](const std::string& name, const std::string& text) {
    const ScratchProgram file(name, text);
    const std::size_t from_file = ProgramReader::open_file(file.path(), "test.ngc").line_count();
    CHECK(ProgramReader(text, "test.ngc").line_count() == from_file);
    return from_file;
  };
  CHECK(count("empty", "") == 0);
  CHECK(count("one", "G0 X1") == 1);
  CHECK(count("one_newline", "G0 X1\n") == 1);
  CHECK(count("blank_last", "G0 X1\n\n") == 2);
  CHECK(count("crlf", "G0 X1\r\nG0 X2\r\n") == 2);
  CHECK(count("cr_last", "G0 X1\n\r") == 2);
}
