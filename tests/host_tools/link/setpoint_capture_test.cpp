// SPDX-License-Identifier: MIT
// SetpointCapture: records made from the wire as the setpoints arrive (issue 19.7). Expected values
// by hand: time = index / rate, position = raw / 65536, speed = |Δraw| / 65536 · rate between
// consecutive indices, 0 after a gap.
#include <array>
#include <cstdint>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/host/link/setpoint_capture.hpp>

using curvestep::host::SetpointRecord;
using curvestep::host::link::SetpointCapture;

TEST_CASE("setpoint capture: records, gaps as standing ticks, duplicates dropped", "[host_tools][stream][capture]") {
  std::vector<SetpointRecord> sunk;
  SetpointCapture capture([&sunk](const SetpointRecord& r) { sunk.push_back(r); });
  capture.set_rate_hz(1000);
  capture.receive(5, {0, 0, 0});
  capture.receive(6, {3 * 65536, 4 * 65536, 0});  // 5 mm in 1 ms
  capture.receive(6, {0, 0, 0});                  // the same index again
  capture.receive(9, {3 * 65536, 4 * 65536, 65536});  // after ticks 7 and 8 stood
  capture.receive(8, {0, 0, 0});                  // behind the stream: dropped
  capture.receive(10, {3 * 65536, 4 * 65536, 65536});
  REQUIRE(sunk.size() == 4);
  CHECK(capture.records().empty());
  CHECK(capture.received() == 4);
  CHECK(capture.duplicates() == 2);
  CHECK(capture.last_index() == 10);
  CHECK(capture.first_run_end() == 6);
  CHECK(capture.standing_ticks(10) == 2);
  CHECK(capture.standing_ticks(14) == 2 + 3);  // the controller ended at index 14: 11, 12, 13 stood too
  CHECK(sunk[0].index == 5);
  CHECK(sunk[0].time_s == Approx(0.005));
  CHECK(sunk[0].speed_mm_per_s == 0);
  CHECK(sunk[1].position_mm == std::array<double, 3>{3, 4, 0});
  CHECK(sunk[1].raw_q16 == std::array<std::int32_t, 3>{3 * 65536, 4 * 65536, 0});
  CHECK(sunk[1].speed_mm_per_s == Approx(5000));
  CHECK(sunk[2].index == 9);
  CHECK(sunk[2].speed_mm_per_s == 0);  // not consecutive
  CHECK(sunk[3].speed_mm_per_s == 0);  // standing still
}

TEST_CASE("setpoint capture: without a sink the records are kept", "[host_tools][stream][capture]") {
  SetpointCapture capture;
  capture.set_rate_hz(500);
  capture.receive(0, {65536, 0, 0});
  capture.receive(1, {2 * 65536, 0, 0});
  REQUIRE(capture.records().size() == 2);
  CHECK(capture.records()[1].time_s == Approx(0.002));
  CHECK(capture.records()[1].speed_mm_per_s == Approx(500));
  CHECK(capture.standing_ticks(2) == 0);
}
