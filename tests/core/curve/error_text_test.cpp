// SPDX-License-Identifier: MIT
// Every Error code has a description, a unique number and a row in docs/errors.md.
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include <catch2/catch.hpp>

#include <curvestep/core/error.hpp>
#include <curvestep/core/error_text.hpp>

using namespace curvestep;

namespace {

/// docs/errors.md, found from this file's path (tests/core/curve/error_text_test.cpp).
std::string read_errors_markdown() {
  std::string path = __FILE__;
  for (int up = 0; up < 4; ++up) {
    const auto slash = path.find_last_of('/');
    REQUIRE(slash != std::string::npos);
    path.resize(slash);
  }
  std::ifstream file(path + "/docs/errors.md");
  INFO("reading " << path << "/docs/errors.md");
  REQUIRE(file.good());
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

}  // namespace

TEST_CASE("errors: every code has a description a unique number and a documented row", "[core][error]") {
  const std::string markdown = read_errors_markdown();
  std::set<int> numbers;
  std::set<std::string_view> names;
  std::size_t count = 0;
  for (const Error e : all_errors) {
    const int number = static_cast<int>(e);
    const std::string_view name = error_name(e);
    INFO("code " << number << " " << name);
    CHECK_FALSE(describe(e).empty());
    CHECK(describe(e) != "unknown error");
    CHECK(name != "Unknown");
    CHECK(numbers.insert(number).second);
    CHECK(names.insert(name).second);
    CHECK(number > 0);
    // The generated table row: "| <number> | `<Name>` | <description> |".
    const std::string row = "| " + std::to_string(number) + " | `" + std::string(name) + "` | " + std::string(describe(e)) + " |";
    CHECK(markdown.find(row) != std::string::npos);
    ++count;
  }
  CHECK(count == numbers.size());
  // Numbers are listed in increasing order (all_errors is documented as numeric order).
  int previous = 0;
  for (const Error e : all_errors) {
    CHECK(static_cast<int>(e) > previous);
    previous = static_cast<int>(e);
  }
  // Nothing in the code table that all_errors lacks: count its rows ("| <digits> |") from its header
  // to the first line that is not a row (later tables, such as LimitField's, are not codes).
  std::istringstream lines(markdown);
  std::string line;
  std::size_t rows = 0;
  bool in_table = false;
  while (std::getline(lines, line)) {
    if (line.rfind("| code | name | meaning |", 0) == 0) {
      in_table = true;
      continue;
    }
    if (!in_table) continue;
    if (line.rfind("|", 0) != 0) break;
    if (line.size() > 2 && line[1] == ' ' && line[2] >= '0' && line[2] <= '9') ++rows;
  }
  CHECK(rows == count);
  // An unlisted value is reported as unknown, not as some other code.
  CHECK(error_name(static_cast<Error>(255)) == "Unknown");
  CHECK(describe(static_cast<Error>(255)) == "unknown error");
}
