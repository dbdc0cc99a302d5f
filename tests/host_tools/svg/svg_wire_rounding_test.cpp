// SPDX-License-Identifier: MIT
// The importer rounds weights and the feed to the nearest Q16.16 value, as the wire carries them
// (docs/job_format.md "Weights and feeds"). Expected values are worked out by hand here
// (value · 65536 rounded to the nearest integer).
#include <cmath>
#include <limits>
#include <string>

#include <catch2/catch.hpp>

#include <curvestep/core/error.hpp>
#include <curvestep/host/svg_import.hpp>

#include "svg_geometry.hpp"
#include "svg_test_support.hpp"

using namespace curvestep;
using namespace curvestep::host;
using namespace curvestep::testing;

namespace {

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

/// The LoadError of importing a one-line page with `feed`.
LoadError feed_error(double feed) {
  SvgOptions options;
  options.feed_mm_per_s = feed;
  try {
    (void)import_page("<line x2=\"10\"/>", options);
  } catch (const LoadError& e) {
    return e;
  }
  FAIL("the page imported with feed " << feed);
  return LoadError({}, "", Error::InvalidArgument);
}

}  // namespace

TEST_CASE("svg: the feed option is rounded to the nearest Q16.16 value", "[host_tools][svg][wire]") {
  // 33.33333 · 65536 = 2184533.11 -> 2184533; 0.1 · 65536 = 6553.6 -> 6554.
  for (const auto& [feed, expected] : {std::pair{33.33333, 2184533.0 / 65536.0}, std::pair{0.1, 6554.0 / 65536.0}}) {
    SvgOptions options;
    options.feed_mm_per_s = feed;
    const Job job = import_page("<circle cx=\"50\" cy=\"50\" r=\"10\"/><line x1=\"1\" x2=\"9\"/>", options).job;
    REQUIRE(job.segments.size() == 7);  // rapid, four quarters, rapid, line
    for (std::size_t i = 0; i < job.segments.size(); ++i) {
      INFO("segment " << i);
      const bool rapid = job.sources[job.source_index[i]].type == SegmentType::Rapid;
      CHECK(job.segments[i].feed_mm_per_s() == (rapid ? 0.0 : expected));
      CHECK(job.sources[job.source_index[i]].feed_mm_per_s == (rapid ? 0.0 : expected));
    }
  }
  // 0 keeps the machine's default feed.
  const Job plain = import_page("<line x2=\"10\"/>").job;
  for (const auto& segment : plain.segments) CHECK(segment.feed_mm_per_s() == 0.0);
}

TEST_CASE("svg: a feed outside Q16.16, rounding to 0, negative or NaN is an error naming file and option", "[host_tools][svg][wire]") {
  struct Case {
    double feed;
    Error code;
    std::string cause;
  };
  const Case cases[] = {
      {1e6, Error::FixedOverflow, "feed 1e+06 is outside the Q16.16 range (at most 32767.99998)"},
      {7e-6, Error::InvalidArgument, "feed 7e-06 rounds to 0 in Q16.16 (the smallest positive value is 2^-16 = 1.52588e-05)"},
      {-5, Error::InvalidArgument, "feed -5 must be a finite number > 0 (or 0 for the machine default)"},
      {std::numeric_limits<double>::quiet_NaN(), Error::InvalidArgument, "must be a finite number > 0"},
  };
  for (const auto& c : cases) {
    const LoadError e = feed_error(c.feed);
    const std::string what = e.what();
    INFO(what);
    CHECK(e.code() == c.code);
    CHECK(e.location().file == "test.svg");
    CHECK(e.location().field == "feed");
    CHECK(what.rfind("test.svg: feed: ", 0) == 0);
    CHECK(contains(what, c.cause));
  }
  // The smallest feeds that survive: 2^-17 rounds (ties away from zero) to 2^-16.
  SvgOptions options;
  options.feed_mm_per_s = 0x1p-17;
  CHECK(import_page("<line x2=\"10\"/>", options).job.segments.back().feed_mm_per_s() == 0x1p-16);
}

TEST_CASE("svg: weights of every arc kind are on the Q16.16 grid in sources and segments", "[host_tools][svg][wire]") {
  const Job job = import_page(
                      "<circle cx=\"20\" cy=\"20\" r=\"5\"/><ellipse cx=\"50\" cy=\"50\" rx=\"7\" ry=\"3\"/>"
                      "<rect x=\"60\" y=\"60\" width=\"20\" height=\"10\" rx=\"2\"/>"
                      "<path d=\"M 10 80 A 8 5 17 1 0 30 85 a 3 3 0 0 1 4 1\"/>")
                      .job;
  std::size_t rational = 0;
  for (std::size_t i = 0; i < job.segments.size(); ++i) {
    const auto& source = job.sources[job.source_index[i]];
    if (source.type != SegmentType::RationalBezier) continue;
    ++rational;
    const auto& curve = job.segments[i].rational();
    for (std::size_t k = 0; k <= curve.degree(); ++k) {
      INFO("segment " << i << " weight " << k << " = " << curve.weight(k));
      CHECK(on_q16_grid(curve.weight(k)));
      CHECK(curve.weight(k) == source.weights[k]);
    }
  }
  CHECK(rational >= 4 + 4 + 4 + 3);
}

TEST_CASE("svg: each piece records the character of the path command that made it", "[host_tools][svg][wire]") {
  // Positions (1-based): M at 1, L at 7, the repeated pair "20 0" at 14, A at 19, Z at 36, then
  // m at 38 starts a new subpath whose h is at 44.
  const auto subpaths = svg::parse_path_data("M 0 0 L 10 0 20 0 A 5 5 0 0 1 30 0 Z m 1 1 h 4");
  REQUIRE(subpaths.size() == 2);
  const auto& first = subpaths[0].pieces;
  REQUIRE(first.size() == 5);  // two lines, two arc pieces (a half circle), the closing line
  CHECK(first[0].position == 7);
  CHECK(first[1].position == 14);
  CHECK(first[2].kind == svg::PieceKind::Conic);
  CHECK(first[2].position == 19);
  CHECK(first[3].position == 19);
  CHECK(first[4].position == 36);
  REQUIRE(subpaths[1].pieces.size() == 1);
  CHECK(subpaths[1].pieces[0].position == 44);
}
