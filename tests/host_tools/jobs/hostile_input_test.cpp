// SPDX-License-Identifier: MIT
// Hostile job and machine files (issue 19, items 7-9): nesting, NUL bytes, absurd numbers, control
// characters and huge tokens are refused with a short, printable error naming the file and field.
#include <filesystem>
#include <string>

#include <catch2/catch.hpp>

#include <curvestep/core/error.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/load_error.hpp>
#include <curvestep/host/machine_file.hpp>
#include <curvestep/host/printable.hpp>

#include "jobs_test_support.hpp"

using namespace curvestep;
using namespace curvestep::host;
using curvestep::testing::job_example;
using curvestep::testing::run_curvestep;

namespace {

const std::string valid_job = R"({"version": 1, "segments": [{"type": "line", "points": [[0, 0], [10, 0]]}]})";

/// A valid machine file with `key` set to the JSON number text `value`.
std::string machine_with(const std::string& key, const std::string& value) {
  std::string fields[][2] = {{"v_max", "200"}, {"a_max", "2000"},    {"j_max", "50000"},
                             {"feed", "50"},   {"tolerance", "0.01"}, {"rate_hz", "1000"}};
  std::string text = "{\"version\": 1";
  for (auto& field : fields) {
    if (field[0] == key) field[1] = value;
    text += ",\n  \"" + field[0] + "\": " + field[1];
  }
  return text + "\n}\n";
}

/// The LoadError that loading `text` as a job throws (fails the test if it loads).
LoadError job_error(const std::string& text) {
  try {
    (void)parse_job(text, "hostile.json");
  } catch (const LoadError& e) {
    return e;
  }
  FAIL("the job loaded");
  throw std::logic_error("unreachable");
}

LoadError machine_error(const std::string& text) {
  try {
    (void)parse_machine(text, "absurd_machine.json");
  } catch (const LoadError& e) {
    return e;
  }
  FAIL("the machine file loaded");
  throw std::logic_error("unreachable");
}

bool has_control_bytes(const std::string& text) {
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f) return true;
  }
  return false;
}

}  // namespace

TEST_CASE("printable: control characters and invalid UTF-8 become hex escapes, valid UTF-8 stays", "[host_tools][jobs][messages]") {
  CHECK(printable("plain text 1.5") == "plain text 1.5");
  CHECK(printable(std::string("a\x1b[31mred", 9)) == "a\\x1b[31mred");
  CHECK(printable(std::string("nul\0end", 7)) == "nul\\x00end");
  CHECK(printable("two\nlines") == "two\\nlines");
  CHECK(printable("del\x7f") == "del\\x7f");
  CHECK(printable("caf\xc3\xa9") == "caf\xc3\xa9");            // U+00E9, valid: kept
  CHECK(printable("bad\xff\xfe") == "bad\\xff\\xfe");          // never valid in UTF-8
  CHECK(printable("cut\xc3") == "cut\\xc3");                    // truncated sequence
  CHECK(printable("c1\xc2\x9b") == "c1\\xc2\\x9b");             // U+009B, the 8-bit CSI: a control character
  CHECK(printable("over\xc0\xaf") == "over\\xc0\\xaf");         // overlong '/'
  CHECK(printable("sur\xed\xa0\x80") == "sur\\xed\\xa0\\x80");  // a UTF-16 surrogate
}

TEST_CASE("printable: a quoted excerpt is cut to a few dozen characters", "[host_tools][jobs][messages]") {
  CHECK(quoted_excerpt("short") == "short");
  const std::string long_number(100000, '9');
  const std::string excerpt = quoted_excerpt(long_number);
  CHECK(excerpt == std::string(max_quoted_chars, '9') + "...");
  CHECK(max_quoted_chars <= 64);
}

TEST_CASE("jobs: a NUL byte in a JSON job is an error, not the end of the file", "[host_tools][jobs][messages]") {
  // Before: nlohmann's lexer stopped at the NUL and the job loaded (exit 0) without the rest.
  const std::string text = valid_job + std::string("\0", 1) + R"({"more": "ignored"})";
  const LoadError e = job_error(text);
  CHECK(e.location().file == "hostile.json");
  CHECK(e.location().line == 1);
  CHECK(e.location().column == valid_job.size() + 1);
  CHECK_THAT(e.message(), Catch::Contains("NUL byte"));
}

TEST_CASE("jobs: nesting deeper than the limit is refused before parsing", "[host_tools][jobs][limits]") {
  const std::size_t depth = 20000;  // the issue's 40 KB file took 1 GB before the limit
  const std::string text = R"({"version": 1, "comment": )" + std::string(depth, '[') + std::string(depth, ']') +
                           R"(, "segments": [{"type": "line", "points": [[0, 0], [10, 0]]}]})";
  const LoadError e = job_error(text);
  CHECK(e.location().line == 1);
  // The documented limit is 64 levels; the root object is level 1, so the 64th '[' opens level 65.
  CHECK(e.location().column == std::string(R"({"version": 1, "comment": )").size() + 64);
  CHECK_THAT(e.message(), Catch::Contains("nested deeper than 64 levels"));
  CHECK(std::string(e.what()).size() < 300);
}

TEST_CASE("jobs: nesting exactly at the limit still loads, brackets inside strings do not count", "[host_tools][jobs][limits]") {
  const std::string text = R"({"version": 1, "comment": )" + std::string(63, '[') + std::string(63, ']') +
                           R"(, "note": "[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[",)" +
                           R"( "segments": [{"type": "line", "points": [[0, 0], [10, 0]]}]})";
  // "note" is not a job key: the loader must get past parsing to say so.
  const LoadError e = job_error(text);
  CHECK_THAT(e.message(), Catch::Contains("unknown key"));
}

TEST_CASE("jobs: an error quoting a 100 KB number quotes a few dozen characters of it", "[host_tools][jobs][messages]") {
  const std::string huge = "1" + std::string(100000, '0');  // 1e100000: too large for a double
  const std::string text = R"({"version": 1, "segments": [{"type": "line", "points": [[0, 0], [)" + huge + R"(, 0]]}]})";
  const LoadError e = job_error(text);
  CHECK_THAT(e.message(), Catch::Contains("too large"));
  CHECK(std::string(e.what()).size() < 200);
  const std::string bad_literal = R"({"version": 1, "segments": [{"type": "line", "points": [[0, 0], [-)" +
                                  std::string(100000, 'x') + R"(, 0]]}]})";
  const LoadError syntax = job_error(bad_literal);
  CHECK_THAT(syntax.message(), Catch::Contains("invalid JSON"));
  CHECK(std::string(syntax.what()).size() < 300);
}

TEST_CASE("jobs: control characters from the file are escaped in the error", "[host_tools][jobs][messages]") {
  const std::string text = "{\"version\": 1, \"segments\": [{\"type\": \"line\\u001b[2J\", \"points\": [[0, 0], [1, 0]]}]}";
  const LoadError e = job_error(text);
  const std::string what = e.what();
  CHECK_FALSE(has_control_bytes(what));
  CHECK_THAT(what, Catch::Contains("line\\x1b[2J"));
}

TEST_CASE("machine files: absurdly small or large limits name the field and the machine file", "[host_tools][jobs][limits]") {
  struct Absurd {
    const char* key;
    const char* value;
  };
  const Absurd cases[] = {
      {"tolerance", "1e-300"}, {"v_max", "1e-300"}, {"a_max", "1e-300"}, {"feed", "1e-300"},
      {"a_max", "5e-324"},     {"j_max", "1e300"},  {"v_max", "1e9"},
  };
  for (const Absurd& absurd : cases) {
    INFO(absurd.key << " = " << absurd.value);
    const LoadError e = machine_error(machine_with(absurd.key, absurd.value));
    CHECK(e.code() == Error::InvalidLimit);
    CHECK(e.location().file == "absurd_machine.json");
    CHECK(e.location().field == std::string("\"") + absurd.key + "\"");
    CHECK_THAT(e.message(), Catch::Contains("outside the plausible range"));
    CHECK(e.location().line > 1);
  }
}

TEST_CASE("machine files: limits inside the plausible ranges load", "[host_tools][jobs][limits]") {
  CHECK_NOTHROW(parse_machine(machine_with("tolerance", "0.0001"), "m.json"));
  CHECK_NOTHROW(parse_machine(machine_with("j_max", "1e9"), "m.json"));
  CHECK_NOTHROW(parse_machine(machine_with("v_max", "100000"), "m.json"));
  CHECK_NOTHROW(parse_machine(machine_with("a_max", "0.001"), "m.json"));
}

TEST_CASE("cli: --rate nan, 0, negative or out of range is refused, not ignored", "[host_tools][jobs][cli]") {
  const std::string job = "'" + job_example("seed_cubic.json").string() + "'";
  const std::string machine = "'" + job_example("machine.json").string() + "'";
  for (const std::string rate : {"nan", "0", "-1000", "inf", "50", "200000", "1000x"}) {
    INFO("--rate " << rate);
    const auto result = run_curvestep("sim " + job + " --machine " + machine + " --rate=" + rate);
    CHECK(result.exit_code != 0);
    CHECK_THAT(result.err, Catch::Contains("--rate") && Catch::Contains("100 to 100000 Hz"));
  }
  const auto good = run_curvestep("sim " + job + " --machine " + machine + " --rate 2000");
  CHECK(good.exit_code == 0);
}
