// SPDX-License-Identifier: MIT
// CompactSegment (the motion queue's form of a PathSegment): a round trip through compact() and
// expand() gives a segment that evaluates, differentiates and splits bit for bit like the
// original, for every kind, including the pieces of a split; split_off() gives split()'s pieces
// (split() is written with split_off(), so both are also held to a de Casteljau written in the test);
// and a queue of segments with two cusps runs like the pieces pushed one by one.
#include <array>
#include <cstring>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/core/motion/cusps.hpp>
#include <curvestep/core/motion/motion_controller.hpp>

#include <support/de_casteljau.hpp>

#include "motion_test_support.hpp"

using namespace curvestep;

using curvestep::testing::mp;

namespace {

/// Bitwise equality of doubles (distinguishes -0 and +0, equal NaN payloads).
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same_bits(const MachinePoint& a, const MachinePoint& b) {
  return same_bits(a[0], b[0]) && same_bits(a[1], b[1]) && same_bits(a[2], b[2]);
}

/// Every public observation of the two segments agrees bit for bit.
void check_identical(const PathSegment& a, const PathSegment& b) {
  REQUIRE(a.kind() == b.kind());
  CHECK(a.rapid() == b.rapid());
  CHECK(same_bits(a.feed_mm_per_s(), b.feed_mm_per_s()));
  CHECK(same_bits(a.start(), b.start()));
  CHECK(same_bits(a.end(), b.end()));
  for (int k = 0; k <= 64; ++k) {
    const double u = k / 64.0;
    CHECK(same_bits(a.point(u), b.point(u)));
    for (std::size_t order = 1; order <= 3; ++order) CHECK(same_bits(a.derivative(u, order), b.derivative(u, order)));
  }
}

PathSegment round_trip(const PathSegment& s) {
  const auto expanded = PathSegment::expand(s.compact());
  REQUIRE(expanded.has_value());
  return expanded.value();
}

std::vector<PathSegment> one_of_each_kind() {
  std::vector<PathSegment> out;
  out.push_back(PathSegment::make_line(mp(0, 0, 0), mp(10.5, -3.25, 1)).value());
  auto arc = PathSegment::make_arc(mp(10, 0, 0), mp(0, 10.001, 2), mp(0, 0), ArcDirection::CounterClockwise, 1, 0.01).value();
  arc.set_feed_mm_per_s(12.5);
  out.push_back(arc);
  const std::array<MachinePoint, 8> heptic{mp(0, 0, 0), mp(3, 7, 1), mp(5, -2, 0), mp(9, 4, 2),
                                           mp(12, 1, 1), mp(13, 9, 0), mp(17, 3, 1), mp(20, 0, 0)};
  auto bezier = PathSegment::make_bezier(heptic).value();
  bezier.set_rapid(true);
  out.push_back(bezier);
  const std::array<double, 8> weights{1, 0.7, 2.5, 1.25, 0.3, 1.9, 0.8, 1.1};
  out.push_back(PathSegment::make_rational_bezier(heptic, weights).value());
  const std::array<MachinePoint, 3> conic{mp(10, 0), mp(10, 10), mp(0, 10)};
  const std::array<double, 3> conic_weights{1, 0.70710678118654752, 1};
  out.push_back(PathSegment::make_rational_bezier(conic, conic_weights).value());
  return out;
}
}  // namespace

TEST_CASE("compact_segment: compact() then expand() keeps every kind bit for bit", "[core][motion]") {
  for (const auto& s : one_of_each_kind()) check_identical(s, round_trip(s));
}

TEST_CASE("compact_segment: the pieces of a split survive the round trip bit for bit", "[core][motion]") {
  for (const auto& s : one_of_each_kind()) {
    if (s.kind() != SegmentKind::Bezier && s.kind() != SegmentKind::RationalBezier) continue;
    for (double u : {0.125, 0.3, 0.77}) {
      const auto halves = s.split(u);
      REQUIRE(halves.has_value());
      check_identical(halves.value().left, round_trip(halves.value().left));
      check_identical(halves.value().right, round_trip(halves.value().right));
      // split again (the homogeneous form of a rational piece is rebuilt by expand())
      const auto again = round_trip(halves.value().right).split(0.5);
      const auto reference = halves.value().right.split(0.5);
      REQUIRE(again.has_value());
      REQUIRE(reference.has_value());
      check_identical(again.value().left, reference.value().left);
      check_identical(again.value().right, reference.value().right);
    }
  }
}

TEST_CASE("compact_segment: split_off gives split's pieces and rejects what split rejects", "[core][motion]") {
  for (const auto& s : one_of_each_kind()) {
    PathSegment right = s;
    PathSegment left;
    const auto halves = s.split(0.4);
    const auto cut = right.split_off(0.4, left);
    REQUIRE(halves.has_value() == cut.has_value());
    if (!cut) {
      CHECK(halves.error() == cut.error());
      check_identical(right, s);  // unchanged
      continue;
    }
    check_identical(left, halves.value().left);
    check_identical(right, halves.value().right);
  }
  PathSegment s = one_of_each_kind()[2];
  PathSegment left;
  CHECK(s.split_off(0, left).error() == Error::InvalidArgument);
  CHECK(s.split_off(1, left).error() == Error::InvalidArgument);
}

TEST_CASE("compact_segment: split_off cuts the Bezier kinds where a de Casteljau written in the test does", "[core][motion]") {
  // lines and arcs are not split (InvalidArgument); the Bézier kinds' pieces have the reference's
  // control points: bit for bit at u = 1/2 (integer points, seven halvings, weights with few
  // bits), within a few roundings of the coordinate scale at u = 0.4
  using curvestep::testing::de_casteljau_split;
  for (const auto& s : one_of_each_kind()) {
    for (const double u : {0.4, 0.5}) {
      PathSegment right = s;
      PathSegment left;
      const auto cut = right.split_off(u, left);
      if (s.kind() == SegmentKind::Line || s.kind() == SegmentKind::Arc) {
        CHECK(cut.error() == Error::InvalidArgument);
        continue;
      }
      REQUIRE(cut.has_value());
      CHECK(left.kind() == s.kind());
      CHECK(right.kind() == s.kind());
      const bool rational = s.kind() == SegmentKind::RationalBezier;
      // homogeneous points (w·P, w); w = 1 for the polynomial kind
      const auto points = rational ? s.rational().control_points() : s.polynomial().control_points();
      std::vector<std::array<long double, 4>> h;
      for (std::size_t i = 0; i < points.size(); ++i) {
        const long double w = rational ? s.rational().weight(i) : 1.0L;
        h.push_back({w * points[i][0], w * points[i][1], w * points[i][2], w});
      }
      const auto reference = de_casteljau_split(h, u);
      const auto check_piece = [&](const PathSegment& piece, const std::vector<std::array<long double, 4>>& expected) {
        const auto actual = rational ? piece.rational().control_points() : piece.polynomial().control_points();
        REQUIRE(actual.size() == expected.size());
        for (std::size_t i = 0; i < actual.size(); ++i) {
          if (rational) CHECK(std::fabs(piece.rational().weight(i) - static_cast<double>(expected[i][3])) <= 1e-14);
          for (std::size_t a = 0; a < 3; ++a) {
            const double want = static_cast<double>(expected[i][a] / expected[i][3]);
            if (u == 0.5 && !rational) {
              CHECK(same_bits(actual[i][a], want));
            } else {
              CHECK(std::fabs(actual[i][a] - want) <= 1e-13 * 32);  // coordinates below 32
            }
          }
        }
      };
      check_piece(left, reference.left);
      check_piece(right, reference.right);
    }
  }
}

TEST_CASE("compact_segment: expand rejects numbers no PathSegment holds", "[core][motion]") {
  CompactSegment c = one_of_each_kind()[2].compact();
  c.degree = 8;
  CHECK(PathSegment::expand(c).error() == Error::DegreeAboveCapacity);
  c = one_of_each_kind()[3].compact();
  c.values[CompactSegment::value_count - 1] = -1;  // weight 7
  CHECK(PathSegment::expand(c).error() == Error::NonPositiveWeight);
}

TEST_CASE("compact_segment: a segment with two cusps runs like its pieces split one after the other", "[core][motion]") {
  // A cubic along x that reverses twice: its hodograph has the Bernstein coefficients 3 (3, -5, 3),
  // i.e. x'(u) = 48 (u - 1/4)(u - 3/4), zero at u = 1/4 and 3/4. Reference: the pieces cut by
  // hand with PathSegment::split in the controller's order, pushed as separate segments.
  const std::array<MachinePoint, 4> points{mp(0, 0), mp(3, 0), mp(-2, 0), mp(1, 0)};
  const auto segment = PathSegment::make_bezier(points).value();
  const auto cusps = find_cusps(segment);
  REQUIRE(cusps.count >= 2);
  std::vector<PathSegment> pieces;
  PathSegment rest = segment;
  double consumed = 0;
  for (std::size_t i = 0; i < cusps.count; ++i) {
    const auto halves = rest.split((cusps.parameters[i] - consumed) / (1 - consumed));
    REQUIRE(halves.has_value());
    pieces.push_back(halves.value().left);
    rest = halves.value().right;
    consumed = cusps.parameters[i];
  }
  pieces.push_back(rest);
  for (const auto& p : pieces) REQUIRE(find_cusps(p).count == 0);

  const MachineLimits m = curvestep::testing::test_machine();
  auto run = [&m](const std::vector<PathSegment>& job) {
    MotionController<Q16_16, 16, 8> controller;
    REQUIRE(controller.configure(m).has_value());
    for (const auto& s : job) REQUIRE(controller.try_push(s, 0).has_value());
    controller.end_of_job();
    REQUIRE(controller.start().has_value());
    std::vector<std::array<std::int32_t, 3>> out;
    while (!controller.finished()) {
      const auto sp = controller.next_setpoint();
      REQUIRE(sp.has_value());
      out.push_back({sp.value().position[0].raw(), sp.value().position[1].raw(), sp.value().position[2].raw()});
      REQUIRE(out.size() < 100000);
    }
    return out;
  };
  const auto whole = run({segment});
  const auto by_pieces = run(pieces);
  CHECK(whole.size() == by_pieces.size());
  CHECK(whole == by_pieces);
}

TEST_CASE("compact_segment: a queue slot is much smaller than a PathSegment", "[core][motion]") {
  CHECK(sizeof(CompactSegment) <= 280);
  CHECK(sizeof(CompactSegment) < sizeof(PathSegment));
}
