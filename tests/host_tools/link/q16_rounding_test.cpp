// SPDX-License-Identifier: MIT
// One rounding to Q16.16 on every host path (issue 25): exact ties go away from zero on the wire
// (to_q16), in the job loader and in the wire's feeds and weights, as docs/protocol.md states.
#include <catch2/catch.hpp>

#include <iomanip>
#include <sstream>

#include <curvestep/host/job.hpp>
#include <curvestep/host/link/wire.hpp>
#include <curvestep/host/wire_value.hpp>

using namespace curvestep;
using namespace curvestep::host;

TEST_CASE("q16 rounding: exact ties go away from zero on every host path", "[host][link][rounding]") {
  // value × 65536 = k + 0.5 exactly: to nearest-even would give 2, -2, 0 and 4 here.
  const struct {
    double mm;
    std::int32_t raw;
  } ties[] = {{2.5 / 65536, 3}, {-2.5 / 65536, -3}, {0.5 / 65536, 1}, {3.5 / 65536, 4}, {1000.5 / 65536, 1001}};
  for (const auto& t : ties) {
    INFO(t.mm);
    bool exact = true;
    CHECK(link::to_q16(t.mm, exact) == t.raw);
    CHECK_FALSE(exact);
    CHECK(round_for_wire(t.mm, WireQuantity::Feed).value == static_cast<double>(t.raw) / 65536);
    // The job loader quantises coordinates with the same rule (the decimal is the exact binary value).
    std::ostringstream text;
    text << std::setprecision(25) << R"({"version": 1, "segments": [{"type": "line", "points": [[0, 1], [)" << t.mm
         << ", 2]]}]}";
    const Job job = parse_job(text.str(), "tie.json");
    CHECK(job.segments.front().end()[0] == static_cast<double>(t.raw) / 65536);
  }
  bool exact = true;
  CHECK(link::to_q16(1.25, exact) == 81920);
  CHECK(exact);
}
