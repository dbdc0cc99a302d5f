// SPDX-License-Identifier: MIT
#include <curvestep/host/link/tick_timing_text.hpp>

#include <cmath>

namespace curvestep::host::link {
namespace {

/// "the 1000 us period" at 1 kHz ("the period" if the rate is unknown).
std::string period_text(double rate_hz) {
  if (!(rate_hz > 0)) return "the period";
  return "the " + std::to_string(std::lround(1e6 / rate_hz)) + " us period";
}

}  // namespace

std::string tick_overrun_text(std::uint32_t overruns, std::uint32_t worst_tick_us) {
  if (overruns == 0) return "";
  return "; tick overruns: " + std::to_string(overruns) + " (worst tick " + std::to_string(worst_tick_us) + " us)";
}

std::string format_tick_timing(std::uint32_t overruns, std::uint32_t worst_tick_us, double rate_hz) {
  std::string line = "  tick overruns:       " + std::to_string(overruns);
  if (worst_tick_us == 0 && overruns == 0) return line + " (ticks not timed by the controller)\n";
  return line + " (worst tick " + std::to_string(worst_tick_us) + " us of " + period_text(rate_hz) + ")\n";
}

std::string tick_overrun_warning(const std::string& command, std::uint32_t overruns, std::uint32_t worst_tick_us,
                                 double rate_hz) {
  if (overruns == 0) return "";
  return command + ": warning: " + std::to_string(overruns) + " control tick" + (overruns == 1 ? " was" : "s were") +
         " late or longer than " + period_text(rate_hz) + " (worst tick " + std::to_string(worst_tick_us) +
         " us): the controller did not keep real time, its steps may have stuttered\n";
}

}  // namespace curvestep::host::link
