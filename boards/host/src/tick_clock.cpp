// SPDX-License-Identifier: MIT
#include <curvestep/boards/host/tick_clock.hpp>

#include <cerrno>

namespace curvestep::boards::host {
namespace {

constexpr std::int64_t ns_per_s = 1000000000;

std::int64_t to_ns(const timespec& t) noexcept { return static_cast<std::int64_t>(t.tv_sec) * ns_per_s + t.tv_nsec; }

timespec from_ns(std::int64_t ns) noexcept {
  timespec t{};
  t.tv_sec = static_cast<time_t>(ns / ns_per_s);
  t.tv_nsec = static_cast<long>(ns % ns_per_s);
  return t;
}

}  // namespace

timespec TickClock::now() noexcept {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t;
}

void TickClock::start(std::uint32_t rate_hz) noexcept {
  rate_hz_ = rate_hz;
  ticks_ = 0;
  origin_ = now();
  deadline_ = origin_;
}

std::int64_t TickClock::remaining_ns() const noexcept { return to_ns(deadline_) - to_ns(now()); }

void TickClock::sleep_until_due() const noexcept {
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &deadline_, nullptr) == EINTR) {
  }
}

void TickClock::advance() noexcept {
  if (rate_hz_ == 0) return;
  ++ticks_;
  // Deadline k = origin + k / rate, computed from the origin so rounding never accumulates.
  const std::int64_t offset = static_cast<std::int64_t>(ticks_ * static_cast<std::uint64_t>(ns_per_s) / rate_hz_);
  deadline_ = from_ns(to_ns(origin_) + offset);
  const std::int64_t period = ns_per_s / rate_hz_;
  if (-remaining_ns() > 100 * period) {
    ++overruns_;
    ticks_ = 0;
    origin_ = now();
    deadline_ = origin_;
  }
}

}  // namespace curvestep::boards::host
