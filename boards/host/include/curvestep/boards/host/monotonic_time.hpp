// SPDX-License-Identifier: MIT
// CLOCK_MONOTONIC as integer nanoseconds, and sleeping to an absolute deadline: the host board's
// one conversion between timespec and ns (TickClock, EdgeClock, GpiodStepOutput).
#pragma once

#include <cerrno>
#include <cstdint>
#include <ctime>

namespace curvestep::boards::host {

/// Nanoseconds of a CLOCK_MONOTONIC reading.
[[nodiscard]] constexpr std::int64_t to_nanoseconds(const timespec& t) noexcept {
  return std::int64_t{t.tv_sec} * 1'000'000'000 + t.tv_nsec;
}

/// The timespec of `ns` nanoseconds (ns >= 0).
[[nodiscard]] constexpr timespec to_timespec(std::int64_t ns) noexcept {
  timespec t{};
  t.tv_sec = static_cast<time_t>(ns / 1'000'000'000);
  t.tv_nsec = static_cast<long>(ns % 1'000'000'000);
  return t;
}

/// The current CLOCK_MONOTONIC time.
[[nodiscard]] inline timespec monotonic_now() noexcept {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t;
}

/// Sleeps until CLOCK_MONOTONIC reaches `deadline` (clock_nanosleep, TIMER_ABSTIME; signals resume it).
inline void sleep_until(const timespec& deadline) noexcept {
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &deadline, nullptr) == EINTR) {
  }
}

}  // namespace curvestep::boards::host
