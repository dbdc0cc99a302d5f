// SPDX-License-Identifier: MIT
// Every number of every segment imported from the example and test drawings is on the Q16.16 grid
// the wire carries (coordinates, weights, feeds), so `curvestep sim` and a device see the same job.
//
// The check is independent of the importer's rounding: a value is on the grid when it is finite
// and value · 65536 (exact in double: a power of two) is an integer.
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/host/link/wire.hpp>
#include <curvestep/host/svg_import.hpp>

#include "svg_test_support.hpp"

using namespace curvestep;
using namespace curvestep::host;
using namespace curvestep::testing;

namespace {

/// The SVG files of `directory`, sorted.
std::vector<std::filesystem::path> svg_files(const std::filesystem::path& directory) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(directory)) {
    if (entry.is_regular_file() && entry.path().extension() == ".svg") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

void check_point(const MachinePoint& p, const std::string& what) {
  for (std::size_t axis = 0; axis < motion_axes; ++axis) {
    INFO(what << " axis " << axis << " = " << p[axis]);
    CHECK(on_q16_grid(p[axis]));
  }
}

/// Every coordinate, weight and feed of the job's PathSegments and SourceSegments.
std::size_t check_job(const Job& job) {
  std::size_t numbers = 0;
  for (std::size_t i = 0; i < job.segments.size(); ++i) {
    const PathSegment& segment = job.segments[i];
    INFO("segment " << i);
    check_point(segment.start(), "start");
    check_point(segment.end(), "end");
    CHECK(on_q16_grid(segment.feed_mm_per_s()));
    numbers += 7;
    switch (segment.kind()) {
      case SegmentKind::Line:
      case SegmentKind::Bezier:
        for (const auto& p : segment.polynomial().control_points()) check_point(p, "control point");
        numbers += 3 * segment.polynomial().control_points().size();
        break;
      case SegmentKind::RationalBezier: {
        const auto& curve = segment.rational();
        for (std::size_t k = 0; k <= curve.degree(); ++k) {
          check_point(curve.control_points()[k], "control point");
          INFO("weight " << k << " = " << curve.weight(k));
          CHECK(on_q16_grid(curve.weight(k)));
          CHECK(curve.weight(k) > 0);
          numbers += 4;
        }
        break;
      }
      case SegmentKind::Arc:
        FAIL("the SVG importer makes no arc segments");
        break;
    }
  }
  for (std::size_t i = 0; i < job.sources.size(); ++i) {
    const SourceSegment& source = job.sources[i];
    INFO("source " << i);
    for (const auto& p : source.points) check_point(p, "source point");
    for (const double w : source.weights) {
      INFO("source weight " << w);
      CHECK(on_q16_grid(w));
    }
    CHECK(on_q16_grid(source.feed_mm_per_s));
    numbers += 3 * source.points.size() + source.weights.size() + 1;
  }
  return numbers;
}

}  // namespace

TEST_CASE("svg: every coordinate, weight and feed imported from the example and test drawings is on the Q16.16 grid",
          "[host_tools][svg][wire]") {
  std::vector<std::filesystem::path> files = svg_files(CURVESTEP_SVG_EXAMPLES);
  for (const auto& directory : {std::filesystem::path(CURVESTEP_SVG_TEST_DATA), std::filesystem::path(CURVESTEP_SVG_FUZZ_CORPUS)}) {
    const auto more = svg_files(directory);
    files.insert(files.end(), more.begin(), more.end());
  }
  REQUIRE(files.size() >= 3);
  // The defaults; the optimiser (reversed pieces) with a feed and a start off the grid
  // (12.345 · 65536 = 809041.92, 0.1 · 65536 = 6553.6: both must be rounded to be sent).
  SvgOptions optimised;
  optimised.optimize = true;
  optimised.feed_mm_per_s = 12.345;
  optimised.start = MachinePoint{{0.1, 0.3, 0.7}};
  std::size_t imported = 0;
  std::size_t rational = 0;
  for (const auto& file : files) {
    INFO(file.string());
    const bool bad = file.filename().string().rfind("bad_", 0) == 0;
    if (bad) {
      SvgOptions strict;
      strict.strict = true;
      CHECK_THROWS_AS(load_svg(file, strict), LoadError);
      continue;
    }
    for (const SvgOptions& options : {SvgOptions{}, optimised}) {
      INFO("optimize " << options.optimize << ", feed " << options.feed_mm_per_s);
      const SvgImport result = load_svg(file, options);
      CHECK(check_job(result.job) > 0);
      for (const auto& source : result.job.sources) {
        if (source.type == SegmentType::RationalBezier) ++rational;
        if (source.type != SegmentType::Rapid && options.feed_mm_per_s > 0) CHECK(source.feed_mm_per_s == 809042.0 / 65536.0);
      }
      // The first rapid starts at the start point, rounded: (6554, 19661, 45875) / 65536.
      if (options.feed_mm_per_s > 0) {
        CHECK(result.job.segments.front().start() == MachinePoint{{6554.0 / 65536.0, 19661.0 / 65536.0, 45875.0 / 65536.0}});
      }
    }
    ++imported;
  }
  CHECK(imported >= 3);    // the demo, the Inkscape and the Illustrator files at least
  CHECK(rational >= 2 * 40);  // the demo alone has 40 arc pieces
}

TEST_CASE("svg: the demo drawing goes over the wire without a rounding note", "[host_tools][svg][wire]") {
  // Before weights were rounded on import, the wire conversion rounded the 40 arc pieces' weights
  // and said so in 40 "weights rounded to Q16.16" notes: the simulator and the device then ran
  // slightly different curves.
  SvgOptions options;
  options.feed_mm_per_s = 12.345;
  const Job job = load_svg(svg_example("curvestep_demo.svg"), options).job;
  const auto wire = link::to_wire(job, motion_axes, 1000);
  for (const auto& note : wire.notes) UNSCOPED_INFO(note);
  CHECK(wire.notes.empty());
  REQUIRE(wire.segments.size() == job.segments.size());
  std::size_t weights = 0;
  for (std::size_t i = 0; i < job.segments.size(); ++i) {
    if (job.segments[i].kind() != SegmentKind::RationalBezier) continue;
    for (std::size_t k = 0; k <= job.segments[i].rational().degree(); ++k) {
      // The raw Q16.16 weight sent is the imported weight · 65536, exactly.
      CHECK(static_cast<double>(wire.segments[i].weights[k]) == job.segments[i].rational().weight(k) * 65536.0);
      ++weights;
    }
  }
  CHECK(weights == 40 * 3);
}
