// SPDX-License-Identifier: MIT
// Random path data and transforms never crash or hang: they import or raise a LoadError.
#include <random>
#include <string>

#include <catch2/catch.hpp>

#include <curvestep/host/svg_import.hpp>
#include <support/numeric.hpp>

#include "svg_test_support.hpp"

using namespace curvestep;
using namespace curvestep::host;
using namespace curvestep::testing;

TEST_CASE("svg: random path data and transforms import or fail with a LoadError", "[host_tools][svg]") {
  std::mt19937_64 random(test_seed());
  const std::string alphabet = "MmLlHhVvCcSsQqTtAaZz0123456789.-+eE ,  01 1e400 NaN";
  const int count = test_count(300);
  std::size_t imported = 0;
  for (int n = 0; n < count; ++n) {
    // A valid path of random commands, then (every other time) a few random characters overwritten.
    std::string d = "M 1 2";
    const std::string commands = "MmLlHhVvCcSsQqTtAaZz";
    const std::size_t arguments[] = {2, 2, 2, 2, 1, 1, 1, 1, 6, 6, 4, 4, 4, 4, 2, 2, 7, 7, 0, 0};
    const auto length = 1 + random() % 8;
    for (std::size_t i = 0; i < length; ++i) {
      const auto which = random() % commands.size();
      d += " ";
      d += commands[which];
      for (std::size_t k = 0; k < arguments[which]; ++k) {
        const bool flag = (commands[which] == 'A' || commands[which] == 'a') && (k == 3 || k == 4);
        d += " " + std::to_string(flag ? random() % 2 : random() % 50);
      }
    }
    if (n % 2 == 1) {
      for (int k = 0; k < 3; ++k) d[random() % d.size()] = alphabet[random() % alphabet.size()];
    }
    std::string transform = random() % 2 == 0 ? "" : " transform=\"rotate(" + std::to_string(random() % 360) + " 3 4) skewX(10)\"";
    INFO(d);
    try {
      const auto result = import_page("<path" + transform + " d=\"" + d + "\"/>");
      check_connected(result.job);
      ++imported;
    } catch (const LoadError& error) {
      const std::string what = error.what();
      INFO(what);
      const bool syntax = what.rfind("test.svg:2: <path> \"d\": at character ", 0) == 0;
      const bool nothing = what.rfind("test.svg:1: <svg>: the drawing has no paths or shapes to draw", 0) == 0;
      CHECK((syntax || nothing));
    }
  }
  CHECK(imported > 0);
}
