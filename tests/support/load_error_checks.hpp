// SPDX-License-Identifier: MIT
// Checks shared by the host tools' bad-file tests (jobs, machine files, SVG drawings): a file is
// rejected with a LoadError whose code, location and message name what is wrong.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include <catch2/catch.hpp>

#include <curvestep/core/error.hpp>
#include <curvestep/host/load_error.hpp>

namespace curvestep::testing {

inline bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

/// What a rejected file must report.
struct ExpectedLoadError {
  std::string path;
  std::size_t line;   ///< 0: the file as a whole (no line in the message)
  std::string field;  ///< the location's field
  Error code;
  std::string cause;  ///< a phrase of the message (the cause without the location)
};

/// Runs `load`, which must throw a LoadError, and checks it: the code, the location's file, line
/// and field, a message starting with "<path>:<line>:" ("<path>: " for line 0) and naming the
/// cause. Returns the error for the caller's own checks (nothing if the file loaded: a failure).
template <class Load>
std::optional<host::LoadError> check_rejected(Load&& load, const ExpectedLoadError& expected) {
  try {
    (void)load();
  } catch (const host::LoadError& error) {
    const std::string what = error.what();
    INFO(what);
    CHECK(error.code() == expected.code);
    CHECK(error.location().file == expected.path);
    CHECK(error.location().line == expected.line);
    CHECK(error.location().field == expected.field);
    const std::string prefix = expected.path + (expected.line > 0 ? ":" + std::to_string(expected.line) + ":" : std::string(": "));
    CHECK(what.rfind(prefix, 0) == 0);
    CHECK(contains(error.message(), expected.cause));
    return error;
  }
  FAIL_CHECK("the file loaded: " << expected.path);
  return std::nullopt;
}

/// For each case (fields file, line, field, code, cause): the file at data_path(case.file), read by
/// load(path), is rejected as check_rejected() requires; then more(case, error, path, what) runs
/// the caller's own checks with the error's full text.
template <class Cases, class DataPath, class Load, class More>
void check_bad_files(const Cases& cases, DataPath data_path, Load load, More more) {
  for (const auto& bad : cases) {
    INFO(bad.file);
    const auto path = data_path(bad.file);
    const auto error = check_rejected([&] { return load(path); }, {path.string(), bad.line, bad.field, bad.code, bad.cause});
    if (!error) continue;
    const std::string what = error->what();
    INFO(what);
    more(bad, *error, path.string(), what);
  }
}

}  // namespace curvestep::testing
