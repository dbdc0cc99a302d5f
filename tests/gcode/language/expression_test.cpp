// SPDX-License-Identifier: MIT
// The language layer's expressions: LinuxCNC's precedence, functions in degrees, rounding of
// negatives, MOD, comparisons, and the errors that name the expression. Expected values by hand.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include <curvestep/host/gcode/program_reader.hpp>
#include <curvestep/host/load_error.hpp>

using namespace curvestep;
using namespace curvestep::host;
using namespace curvestep::host::gcode;

namespace {

/// The value of `expression` written as the X word of one line.
double x_of(const std::string& expression) {
  const std::string text = "G1 X" + expression;  // the reader keeps views into its text
  ProgramReader reader(text, "expr.ngc");
  const auto block = reader.next();
  REQUIRE(block);
  const ProgramWord* x = block->find('X');
  REQUIRE(x != nullptr);
  return x->value;
}

/// The LoadError that reading `program` to its end throws.
LoadError error_of(const std::string& program) {
  try {
    ProgramReader reader(program, "bad.ngc");
    while (reader.next()) {
    }
  } catch (const LoadError& error) {
    return error;
  }
  FAIL("no error for: " << program);
  return LoadError({}, "", Error::GcodeSyntax);
}

}  // namespace

TEST_CASE("language: precedence is ** then * / MOD then + - then comparisons then AND OR XOR", "[gcode][language][expression]") {
  CHECK(x_of("[2+3*4**2]") == 50.0);                     // 4**2=16, *3=48, +2
  CHECK(x_of("[2**3**2]") == 64.0);                      // left to right: (2**3)**2
  CHECK(x_of("[10-4-3]") == 3.0);                        // left to right
  CHECK(x_of("[12/3/2]") == 2.0);
  CHECK(x_of("[1+2 GT 2]") == 1.0);                      // 3 > 2
  CHECK(x_of("[1 + 2 EQ 3 AND 0]") == 0.0);              // (3 EQ 3) AND 0
  CHECK(x_of("[0 OR 2 LT 1]") == 0.0);                   // 0 OR (2<1)
  CHECK(x_of("[1 XOR 1 EQ 1]") == 0.0);                  // 1 XOR (1 EQ 1)
  CHECK(x_of("[7 MOD 4 * 2]") == 6.0);                   // same level, left to right: (7 MOD 4)*2
  CHECK(x_of("[-2**2]") == 4.0);                         // the sign belongs to the value (LinuxCNC)
  CHECK(x_of("[2*-3]") == -6.0);
  CHECK(x_of("[2--3]") == 5.0);
  CHECK(x_of("-[1+1]") == -2.0);
  CHECK(x_of("[[1+2]*[3+4]]") == 21.0);
}

TEST_CASE("language: blanks anywhere and any letter case", "[gcode][language][expression]") {
  CHECK(x_of("[ 2 + 3 * 4 ** 2 ]") == 50.0);
  CHECK(x_of("[1 m o d 1]") == 0.0);
  CHECK(x_of("a b s [ -3 ]") == 3.0);
  CHECK(x_of("[3 Gt 2]") == 1.0);
}

TEST_CASE("language: functions, angles in degrees", "[gcode][language][expression]") {
  CHECK(x_of("ATAN[1]/[1]") == Approx(45.0));
  CHECK(x_of("ATAN[1]/[-1]") == Approx(135.0));
  CHECK(x_of("ATAN[-1]/[0]") == Approx(-90.0));
  CHECK(x_of("SIN[30]") == Approx(0.5));
  CHECK(x_of("COS[60]") == Approx(0.5));
  CHECK(x_of("TAN[45]") == Approx(1.0));
  CHECK(x_of("ASIN[1]") == Approx(90.0));
  CHECK(x_of("ACOS[0]") == Approx(90.0));
  CHECK(x_of("SQRT[16]") == 4.0);
  CHECK(x_of("ABS[-2.5]") == 2.5);
  CHECK(x_of("EXP[0]") == 1.0);
  CHECK(x_of("LN[1]") == 0.0);
  CHECK(x_of("[2 * SIN[90] + COS[0]]") == Approx(3.0));
}

TEST_CASE("language: FIX rounds down, FUP up, ROUND half away from zero (negatives too)", "[gcode][language][expression]") {
  CHECK(x_of("FIX[2.7]") == 2.0);
  CHECK(x_of("FIX[-2.3]") == -3.0);
  CHECK(x_of("FUP[2.3]") == 3.0);
  CHECK(x_of("FUP[-2.7]") == -2.0);
  CHECK(x_of("ROUND[2.5]") == 3.0);
  CHECK(x_of("ROUND[-2.5]") == -3.0);
  CHECK(x_of("ROUND[-2.4]") == -2.0);
}

TEST_CASE("language: MOD of negatives is never negative (LinuxCNC adds |b|)", "[gcode][language][expression]") {
  CHECK(x_of("[7 MOD 3]") == 1.0);
  CHECK(x_of("[-7 MOD 3]") == 2.0);    // fmod -1, + 3
  CHECK(x_of("[7 MOD -3]") == 1.0);
  CHECK(x_of("[-7 MOD -3]") == 2.0);   // fmod -1, + 3
  CHECK(x_of("[7.5 MOD 2]") == 1.5);
}

TEST_CASE("language: comparisons treat values within 1e-6 as equal (GE LE too)", "[gcode][language][expression]") {
  CHECK(x_of("[1 EQ 1.0000001]") == 1.0);
  CHECK(x_of("[1 NE 1.0000001]") == 0.0);
  CHECK(x_of("[1 EQ 1.00001]") == 0.0);
  CHECK(x_of("[1 GE 1.0000001]") == 1.0);
  CHECK(x_of("[1.0000001 LE 1]") == 1.0);
  CHECK(x_of("[1 LT 1.0000001]") == 1.0);
  CHECK(x_of("[2 GT 2]") == 0.0);
  CHECK(x_of("[2 AND 3]") == 1.0);
  CHECK(x_of("[0 OR 0]") == 0.0);
}

TEST_CASE("language: domain errors name file:line:column and the expression", "[gcode][language][expression][errors]") {
  SECTION("division by zero") {
    const LoadError e = error_of("G0 X0\nG1 X[1 + 2/0]");
    CHECK(e.code() == Error::DivisionByZero);
    CHECK(e.location().line == 2);
    CHECK(e.location().column == 10);
    CHECK(e.location().field == "2/0");
    CHECK(std::string(e.what()) == "bad.ngc:2:10: 2/0: division by zero");
  }
  SECTION("MOD by zero") { CHECK(error_of("G1 X[5 MOD 0]").code() == Error::DivisionByZero); }
  SECTION("SQRT of a negative value") {
    const LoadError e = error_of("G1 X SQRT[-4]");
    CHECK(e.code() == Error::GcodeBadNumber);
    CHECK(e.location().column == 6);
    CHECK(e.location().field == "SQRT[-4]");
  }
  SECTION("LN of zero") { CHECK(error_of("G1 XLN[0]").code() == Error::GcodeBadNumber); }
  SECTION("ACOS beyond 1") { CHECK(error_of("G1 XACOS[1.5]").location().field == "ACOS[1.5]"); }
  SECTION("ASIN beyond -1") { CHECK(error_of("G1 XASIN[-2]").code() == Error::GcodeBadNumber); }
  SECTION("a negative value to a fractional power") { CHECK(error_of("G1 X[-8**0.5]").code() == Error::GcodeBadNumber); }
  SECTION("overflow") { CHECK(error_of("G1 XEXP[1000]").code() == Error::GcodeBadNumber); }
}

TEST_CASE("language: syntax errors of expressions", "[gcode][language][expression][errors]") {
  CHECK(error_of("G1 X[1+2").code() == Error::GcodeSyntax);
  CHECK(error_of("G1 X[1 FOO 2]").location().field == "FOO");
  CHECK(error_of("G1 XCOSH[1]").code() == Error::GcodeSyntax);
  CHECK(error_of("G1 XATAN[1]").code() == Error::GcodeSyntax);
  CHECK(error_of("G1 X").code() == Error::GcodeBadNumber);
  CHECK(error_of("G1 X1 X2").code() == Error::GcodeConflictingWords);
  CHECK(error_of("G1 X1 ]").code() == Error::GcodeSyntax);
}
