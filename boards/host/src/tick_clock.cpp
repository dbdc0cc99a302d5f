// SPDX-License-Identifier: MIT
#include <curvestep/boards/host/tick_clock.hpp>

#include <curvestep/boards/host/monotonic_time.hpp>

namespace curvestep::boards::host {
namespace {

constexpr std::int64_t ns_per_s = 1000000000;

}  // namespace

timespec TickClock::now() noexcept { return monotonic_now(); }

void TickClock::start(std::uint32_t rate_hz) noexcept {
  rate_hz_ = rate_hz;
  ticks_ = 0;
  origin_ = now();
  deadline_ = origin_;
}

std::int64_t TickClock::remaining_ns() const noexcept { return to_nanoseconds(deadline_) - to_nanoseconds(now()); }

void TickClock::sleep_until_due() const noexcept { sleep_until(deadline_); }

void TickClock::advance() noexcept {
  if (rate_hz_ == 0) return;
  ++ticks_;
  // Deadline k = origin + k / rate, computed from the origin so rounding never accumulates.
  const std::int64_t offset = static_cast<std::int64_t>(ticks_ * static_cast<std::uint64_t>(ns_per_s) / rate_hz_);
  deadline_ = to_timespec(to_nanoseconds(origin_) + offset);
  const std::int64_t period = ns_per_s / rate_hz_;
  if (-remaining_ns() > 100 * period) {
    ++overruns_;
    ticks_ = 0;
    origin_ = now();
    deadline_ = origin_;
  }
}

}  // namespace curvestep::boards::host
