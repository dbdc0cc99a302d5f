// SPDX-License-Identifier: MIT
// Every bad job and machine file in data/ is rejected with an error naming file, line, segment and field.
#include <string>

#include <catch2/catch.hpp>

#include <curvestep/core/error.hpp>
#include <curvestep/core/error_text.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/machine_file.hpp>

#include <support/load_error_checks.hpp>

#include "jobs_test_support.hpp"

using namespace curvestep;
using namespace curvestep::host;
using curvestep::testing::check_bad_files;
using curvestep::testing::contains;
using curvestep::testing::job_data;

namespace {

struct BadFile {
  const char* file;
  std::size_t line;
  const char* segment;  ///< "segment 3 (bezier)" or "" for a file-level error
  const char* field;
  Error code;
  const char* cause;  ///< a phrase of the message
};

}  // namespace

TEST_CASE("jobs: each bad job file names the file, line, segment and field", "[host_tools][jobs]") {
  const BadFile cases[] = {
      {"bad_missing_points.json", 5, "segment 1 (line)", "\"points\"", Error::InvalidJob, "missing required key"},
      {"bad_wrong_type.json", 5, "segment 0 (bezier)", "\"points\"[1][1]", Error::InvalidJob, "expected a number, got a string"},
      {"bad_knots_decreasing.json", 7, "segment 1 (bspline)", "\"knots\"[5]", Error::KnotsNotNondecreasing, "must not decrease"},
      {"bad_knot_count.json", 6, "segment 0 (bspline)", "\"knots\"", Error::WrongKnotCount, "expected 7 knots"},
      {"bad_disconnected.json", 6, "segment 2 (bezier)", "\"points\"[0]", Error::SegmentsNotConnected,
       "starts at (5, 1, 0), but segment 1 ended at (5, 0.5, 0)"},
      {"bad_weight.json", 6, "segment 0 (rational_bezier)", "\"weights\"[1]", Error::InvalidJob, "must be positive"},
      {"bad_nurbs_weight.json", 6, "segment 0 (nurbs)", "\"weights\"[1]", Error::InvalidJob, "must be positive"},
      {"bad_unknown_type.json", 5, "segment 1", "\"type\"", Error::UnknownSegmentType, "unknown segment type \"spline\""},
      {"bad_nan.json", 5, "segment 1 (line)", "\"points\"[1][1]", Error::InvalidJob, "invalid JSON"},
      {"bad_infinite.json", 4, "segment 0 (bezier)", "\"points\"[1][0]", Error::InvalidJob, "too large"},
      {"bad_out_of_range.json", 9, "segment 3 (bezier)", "\"points\"[2][1]", Error::FixedOverflow,
       "value 1e+09 is outside the Q16.16 range"},
      {"bad_inch_out_of_range.json", 5, "segment 0 (line)", "\"points\"[1][0]", Error::FixedOverflow, "33020 mm"},
      {"bad_unknown_key.json", 5, "segment 0 (rational_bezier)", "\"wieghts\"", Error::InvalidJob, "unknown key"},
      {"bad_arc_end.json", 4, "segment 0 (arc)", "\"points\"[1]", Error::InvalidArgument, "12 mm from the center"},
      {"bad_arc_direction.json", 4, "segment 0 (arc)", "\"direction\"", Error::InvalidJob, "missing required key"},
      {"bad_multiplicity.json", 6, "segment 0 (bspline)", "\"knots\"[3]", Error::KnotMultiplicityTooHigh, "repeated more than 2"},
      {"bad_degree.json", 4, "segment 0 (nurbs)", "\"degree\"", Error::InvalidJob, "from 1 to 7"},
      {"bad_points_shape.json", 5, "segment 1 (line)", "\"points\"[1]", Error::InvalidJob, "got 4"},
      {"bad_version.json", 2, "", "\"version\"", Error::InvalidJob, "unsupported version 2"},
  };
  check_bad_files(cases, job_data, [](const auto& path) { return load_job(path); },
                  [](const BadFile& bad, const LoadError& e, const std::string&, const std::string& what) {
                    CHECK(contains(what, std::string(": ") + bad.field + ": "));
                    CHECK(contains(what, bad.cause));
                    if (std::string(bad.segment).empty()) {
                      CHECK_FALSE(e.location().segment.has_value());
                      CHECK_FALSE(contains(what, "segment"));
                    } else {
                      CHECK(contains(what, std::string(": ") + bad.segment + ": "));
                    }
                    CHECK_FALSE(contains(what, "\n"));
                  });
}

TEST_CASE("jobs: a JSON syntax error gives line and column", "[host_tools][jobs]") {
  try {
    (void)parse_job("{\"version\": 1,\n \"segments\": [\n  {\"type\": \"line\", \"points\": [[0, 0], [1, NaN]]}]}", "syntax.json");
    FAIL("NaN is not JSON");
  } catch (const LoadError& e) {
    CHECK(e.location().line == 3);
    CHECK(e.location().column == 43);  // the N of NaN
    CHECK(std::string(e.what()).rfind("syntax.json:3:43: segment 0 (line): \"points\"[1][1]: invalid JSON", 0) == 0);
  }
}

TEST_CASE("jobs: each bad machine file names the file, line and field", "[host_tools][jobs]") {
  const BadFile cases[] = {
      {"machine_missing_a_max.json", 1, "", "\"a_max\"", Error::InvalidMachine, "missing required key"},
      {"machine_negative_v_max.json", 2, "", "\"v_max\"", Error::InvalidLimit, "value -100 must be positive"},
      {"machine_zero_feed.json", 5, "", "\"feed\"", Error::InvalidLimit, "value 0 must be positive"},
      {"machine_bad_rate.json", 7, "", "\"rate_hz\"", Error::InvalidRate, "outside 100 Hz .. 100 kHz"},
      {"machine_bad_axis.json", 11, "", "\"axes\".\"y\".\"a_max\"", Error::InvalidLimit, "value -5 must not be negative"},
      {"machine_wrong_type.json", 5, "", "\"feed\"", Error::InvalidMachine, "expected a number, got a string"},
      {"machine_bad_profile.json", 8, "", "\"profile\"", Error::InvalidMachine, "unknown profile \"sine\""},
  };
  check_bad_files(cases, job_data, [](const auto& path) { return load_machine(path); },
                  [](const BadFile& bad, const LoadError&, const std::string& path, const std::string& what) {
                    CHECK(what.rfind(path + ":" + std::to_string(bad.line) + ": " + bad.field + ": ", 0) == 0);
                    CHECK(contains(what, bad.cause));
                  });
}

TEST_CASE("jobs: the example machine file maps onto MachineLimits", "[host_tools][jobs]") {
  const MachineLimits limits = load_machine(curvestep::testing::job_example("machine.json"));
  CHECK(limits.v_max_mm_per_s == 200);
  CHECK(limits.a_max_mm_per_s2 == 2000);
  CHECK(limits.j_max_mm_per_s3 == 50000);
  CHECK(limits.feed_mm_per_s == 50);
  CHECK(limits.rapid_mm_per_s == 150);
  CHECK(limits.tolerance_mm == 0.01);
  CHECK(limits.rate_hz == 1000);
  CHECK(limits.junction_deviation_mm == 0.02);
  CHECK(limits.max_step_rate_hz == 40000);
  CHECK(limits.jerk_limited);
  CHECK(limits.axes[0].steps_per_mm == 80);
  CHECK(limits.axes[2].steps_per_mm == 400);
  CHECK(limits.axes[2].v_max_mm_per_s == 20);
  CHECK(limits.axes[2].a_max_mm_per_s2 == 500);
  CHECK(limits.validate().has_value());
}

TEST_CASE("jobs: a machine file without optional keys keeps the defaults and reads the profile", "[host_tools][jobs]") {
  const MachineLimits limits = load_machine(job_data("machine_trapezoid.json"));
  const MachineLimits defaults;
  CHECK_FALSE(limits.jerk_limited);
  CHECK(limits.v_max_mm_per_s == 120);
  CHECK(limits.rate_hz == 2000);
  CHECK(limits.junction_deviation_mm == defaults.junction_deviation_mm);
  CHECK(limits.max_step_rate_hz == defaults.max_step_rate_hz);
  CHECK(limits.axes[1].steps_per_mm == 0);
}

TEST_CASE("jobs: every LimitField has a machine-file name", "[host_tools][jobs]") {
  CHECK(machine_field_name(LimitField::JunctionDeviation) == "\"junction_deviation\"");
  CHECK(machine_field_name(LimitField::AxisStepsPerMm, 2) == "\"axes\".\"z\".\"steps_per_mm\"");
  CHECK(machine_field_name(LimitField::MaxStepRate) == "\"max_step_rate\"");
}
