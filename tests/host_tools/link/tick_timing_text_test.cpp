// SPDX-License-Identifier: MIT
// The controller's tick timing as the operator reads it (tick_timing_text.hpp): the summary line
// of `curvestep stream`, `gpio` and `jog`, the warning, and the text added to a failed upload's
// cause. Expected lines written by hand from docs/firmware.md, "Tick timing".
#include <catch2/catch.hpp>

#include <curvestep/host/link/tick_timing_text.hpp>

using namespace curvestep::host::link;

TEST_CASE("tick timing text: the summary names the overruns and the worst tick against the period",
          "[host_tools][stream][tick]") {
  CHECK(format_tick_timing(0, 42, 1000) == "  tick overruns:       0 (worst tick 42 us of the 1000 us period)\n");
  CHECK(format_tick_timing(7, 2003412, 500) == "  tick overruns:       7 (worst tick 2003412 us of the 2000 us period)\n");
  // A controller that does not time its ticks (a --fast device, a board without a cycle clock).
  CHECK(format_tick_timing(0, 0, 1000) == "  tick overruns:       0 (ticks not timed by the controller)\n");
}

TEST_CASE("tick timing text: a warning only when a tick overran", "[host_tools][stream][tick]") {
  CHECK(tick_overrun_warning("curvestep stream", 0, 312, 1000).empty());
  CHECK(tick_overrun_warning("curvestep stream", 1, 1500, 1000) ==
        "curvestep stream: warning: 1 control tick was late or longer than the 1000 us period (worst tick 1500 us): "
        "the controller did not keep real time, its steps may have stuttered\n");
  CHECK(tick_overrun_warning("curvestep gpio", 12, 800, 1000) ==
        "curvestep gpio: warning: 12 control ticks were late or longer than the 1000 us period (worst tick 800 us): "
        "the controller did not keep real time, its steps may have stuttered\n");
}

TEST_CASE("tick timing text: a failed upload's last state names the overruns, if any", "[host_tools][stream][tick]") {
  CHECK(tick_overrun_text(0, 900).empty());
  CHECK(tick_overrun_text(3, 2100) == "; tick overruns: 3 (worst tick 2100 us)");
}
