// SPDX-License-Identifier: MIT
// Subroutine files through the importer: import_gcode reads name.ngc from the program's folder or
// GcodeOptions::subroutine_path (the --subroutine-path of the commands), its moves join the job at
// the line of the call in the program (a job names one file), and an error in a line of the file
// names that file and line.
#include <catch2/catch.hpp>

#include <string>

#include <curvestep/host/gcode_import.hpp>

#include "../scratch_folder.hpp"

using namespace curvestep;
using namespace curvestep::host;
using namespace curvestep::testing;

namespace {

const char* const square_sub =
    "(square.ngc: a square of side #1 from the point where it is called)\n"
    "o<square> sub\n"
    "  G1 X[#<_x> + #1] F600\n"
    "  G1 Y[#<_y> + #1]\n"
    "  G1 X#<_x0>\n"
    "o<square> endsub\n"
    "M2\n";

}  // namespace

TEST_CASE("subroutine file import: a sub from the subroutine path draws its moves at the call's line", "[gcode][import][subfile]") {
  const ScratchFolder scratch("subfile_import");
  const auto program = scratch.write("part.ngc",
                                     "G21 G90 G0 X1 Y1\n"
                                     "#<_x> = 1\n"
                                     "#<_y> = 1\n"
                                     "#<_x0> = 1\n"
                                     "o<square> call [10]\n"
                                     "G0 X0 Y0\n"
                                     "M2\n");
  scratch.write("lib/square.ngc", square_sub);
  GcodeOptions options;
  options.subroutine_path = {scratch.root() / "lib"};
  // From (1,1): X11, then Y11, then back to X1; the rapid home from line 6.
  const Job job = import_gcode(program, options);
  REQUIRE(job.segments.size() == 5);
  const double ends[5][2] = {{1, 1}, {11, 1}, {11, 11}, {1, 11}, {0, 0}};
  const std::size_t lines[5] = {1, 5, 5, 5, 6};
  for (std::size_t i = 0; i < 5; ++i) {
    INFO("segment " << i);
    CHECK(job.segments[i].end()[0] == Approx(ends[i][0]).margin(1e-9));
    CHECK(job.segments[i].end()[1] == Approx(ends[i][1]).margin(1e-9));
    CHECK(job.sources[i].line == lines[i]);
  }
  // Without the path the file is not found, and the message says where it looked.
  try {
    (void)import_gcode(program);
    FAIL("the sub was found without its folder");
  } catch (const LoadError& e) {
    CHECK(std::string(e.what()) == program.string() + ":5:1: o<square> call: no subroutine o<square> sub in the program, and no file " +
                                       "square.ngc in " + scratch.root().string() + " (the folders searched, in this order)");
  }
}

TEST_CASE("subroutine file import: a text program finds its subs on the subroutine path alone", "[gcode][import][subfile]") {
  const ScratchFolder scratch("subfile_import_text");
  scratch.write("square.ngc", square_sub);
  GcodeOptions options;
  options.subroutine_path = {scratch.root()};
  const Job job = parse_gcode_job("G21 G90 G0 X2 Y3\n#<_x> = 2\n#<_y> = 3\n#<_x0> = 2\no<square> call [4]\n", "text.ngc", options);
  REQUIRE(job.segments.size() == 4);
  CHECK(job.segments[3].end()[0] == Approx(2).margin(1e-9));
  CHECK(job.segments[2].end()[1] == Approx(7).margin(1e-9));
}

TEST_CASE("subroutine file import: the machine layer's errors in a file's line name the file and its line", "[gcode][import][subfile][errors]") {
  const ScratchFolder scratch("subfile_import_errors");
  const auto program = scratch.write("part.ngc", "G21 G90\nG0 X1\no<rotary> call\n");
  scratch.write("rotary.ngc", "o<rotary> sub\nG1 A1 F100\no<rotary> endsub\n");
  try {
    (void)import_gcode(program);
    FAIL("an A word was accepted");
  } catch (const LoadError& e) {
    CHECK(e.code() == Error::GcodeUnsupportedWord);
    CHECK(e.location().file == scratch.path("rotary.ngc"));
    CHECK(e.location().line == 2);
    CHECK(e.location().column == 4);
    CHECK_THAT(std::string(e.what()), Catch::StartsWith(scratch.path("rotary.ngc") + ":2:4: A1: ") && Catch::Contains("rotary"));
  }
}
