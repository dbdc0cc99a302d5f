// SPDX-License-Identifier: MIT
// The controller's tick timing for the operator: how many control ticks started a period late or
// ran longer than one (StatusReport::tick_overruns) and the longest tick, in the summary of
// `curvestep stream`, `gpio` and `jog`, a warning when any tick was late, and the cause of a
// failed upload (docs/firmware.md, "Tick timing").
#pragma once

#include <cstdint>
#include <string>

namespace curvestep::host::link {

/// "" when no tick overran, else "; tick overruns: N (worst tick U us)" (appended to a state).
[[nodiscard]] std::string tick_overrun_text(std::uint32_t overruns, std::uint32_t worst_tick_us);

/// The summary line, e.g. "  tick overruns:       0 (worst tick 42 us of the 1000 us period)\n";
/// "(ticks not timed by the controller)" when the worst tick is 0.
[[nodiscard]] std::string format_tick_timing(std::uint32_t overruns, std::uint32_t worst_tick_us, double rate_hz);

/// "" when no tick overran, else the warning line for stderr: "<command>: warning: N control
/// ticks were late or longer than their period ... the controller did not keep real time\n".
[[nodiscard]] std::string tick_overrun_warning(const std::string& command, std::uint32_t overruns,
                                               std::uint32_t worst_tick_us, double rate_hz);

}  // namespace curvestep::host::link
