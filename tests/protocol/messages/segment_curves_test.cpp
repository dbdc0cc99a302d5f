// SPDX-License-Identifier: MIT
// Segments and core curves convert into each other exactly, through the wire.
#include <catch2/catch.hpp>

#include <array>
#include <vector>

#include <curvestep/protocol/segment_curves.hpp>
#include <support/numeric.hpp>

using namespace curvestep;
using namespace curvestep::protocol;
using curvestep::testing::point;

namespace {

QueueSegment through_wire(const QueueSegment& s) {
  std::array<std::byte, max_payload_size> payload{};
  const auto size = encode(s, payload);
  REQUIRE(size.has_value());
  const auto back = decode<QueueSegment>(std::span<const std::byte>(payload.data(), size.value()));
  REQUIRE(back.has_value());
  return back.value();
}

}  // namespace

TEST_CASE("segment curves: a cubic survives the wire bit for bit", "[protocol][messages]") {
  const auto cubic = Bezier<Q16_16, 3, 7>::create({point<Q16_16>(0, 0, 0), point<Q16_16>(1.5, 2.25, 0.5),
                                                   point<Q16_16>(-3.125, 4, 1), point<Q16_16>(10, -0.0625, 2)});
  REQUIRE(cubic.has_value());
  const auto segment = bezier_segment(cubic.value());
  REQUIRE(segment.has_value());
  CHECK(segment.value().degree == 3);
  CHECK(segment.value().points[1][1] == 147456);  // 2.25 * 65536
  const auto back = to_bezier<3>(through_wire(segment.value()));
  REQUIRE(back.has_value());
  REQUIRE(back.value().degree() == 3);
  for (std::size_t i = 0; i <= 3; ++i) CHECK(back.value()[i] == cubic.value()[i]);
}

TEST_CASE("segment curves: a rational quadratic keeps its weights exactly", "[protocol][messages]") {
  // A quarter circle: weights 1, sqrt(2)/2, 1 (46341 raw is the nearest Q16.16 to 0.7071068).
  const auto arc = RationalBezier<Q16_16, 2, 7>::create({point<Q16_16>(1, 0), point<Q16_16>(1, 1), point<Q16_16>(0, 1)},
                                                        {Q16_16(1), Q16_16::from_raw(46341), Q16_16(1)});
  REQUIRE(arc.has_value());
  const auto segment = rational_bezier_segment(arc.value());
  REQUIRE(segment.has_value());
  CHECK(segment.value().weights[1] == 46341);
  const auto back = to_rational_bezier<2>(through_wire(segment.value()));
  REQUIRE(back.has_value());
  for (std::size_t i = 0; i <= 2; ++i) {
    CHECK(back.value().control_points()[i] == arc.value().control_points()[i]);
    CHECK(back.value().weight(i) == arc.value().weight(i));
  }
}

TEST_CASE("segment curves: a line becomes a degree-1 Bezier and a rational with unit weights", "[protocol][messages]") {
  const QueueSegment line = line_segment<2>(point<Q16_16>(1, 2), point<Q16_16>(3.5, -4));
  const auto polynomial = to_bezier<2>(through_wire(line));
  REQUIRE(polynomial.has_value());
  CHECK(polynomial.value().degree() == 1);
  CHECK(polynomial.value()[1] == point<Q16_16>(3.5, -4));
  const auto rational = to_rational_bezier<2>(line);
  REQUIRE(rational.has_value());
  CHECK(rational.value().weight(0) == Q16_16(1));
  CHECK(rational.value().weight(1) == Q16_16(1));
}

TEST_CASE("segment curves: an arc keeps centre, end, direction and helical Z", "[protocol][messages]") {
  const QueueSegment arc = arc_segment<3>(point<Q16_16>(1, 0, 0), point<Q16_16>(0, 1, 2.5), point<Q16_16>(0, 0),
                                          ArcDirection::Clockwise);
  const QueueSegment back = through_wire(arc);
  CHECK(back.kind == SegmentKind::Arc);
  CHECK(back.direction == ArcDirection::Clockwise);
  CHECK(back.points[1] == WirePoint{0, 65536, 163840});
  CHECK(back.points[2] == WirePoint{0, 0, 0});
  CHECK(to_bezier<3>(back).error() == Error::InvalidArgument);
}

TEST_CASE("segment curves: mismatched axes and oversized degrees are refused", "[protocol][messages]") {
  const QueueSegment line = line_segment<3>(point<Q16_16>(0, 0, 0), point<Q16_16>(1, 1, 1));
  const auto wrong_axes = to_bezier<2>(line);
  REQUIRE_FALSE(wrong_axes.has_value());
  CHECK(wrong_axes.error() == Error::InvalidArgument);
  CHECK(wrong_axes.where() == 1);

  QueueSegment septic;
  septic.kind = SegmentKind::Bezier;
  septic.axis_count = 2;
  septic.degree = 7;
  const auto small = to_bezier<2, 3>(septic);
  REQUIRE_FALSE(small.has_value());
  CHECK(small.error() == Error::DegreeAboveCapacity);

  std::vector<Vec2<Q16_16>> nine;
  for (int i = 0; i < 9; ++i) nine.push_back(point<Q16_16>(i, i));
  const auto octic = Bezier<Q16_16, 2, 8>::create(nine);
  REQUIRE(octic.has_value());
  CHECK(bezier_segment(octic.value()).error() == Error::DegreeAboveCapacity);
}
