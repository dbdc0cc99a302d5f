// SPDX-License-Identifier: MIT
// LinkWatch: the App's watch over a silent host and a backed-up setpoint stream.
//
// * Link loss: no valid frame for settings.link_timeout_ms (LinkReceiver::check_link). The App acts
//   on a loss once (a feed hold and ErrorReport(LinkTimeout)); the next valid frame re-arms it.
// * Stall: a tick that finds the setpoint stream full advances nothing (App::on_tick). A stall
//   that lasts settings.stall_timeout_ms while moving is a fault, named by what the host did
//   meanwhile (stall_fault): a host heard during the stall talks but does not take the setpoints
//   (RetransmitLimit), a silent one is gone (LinkTimeout), and without a planner a queue the host
//   did not refill in time is QueueUnderrun (docs/firmware.md, "Safety states").
// Time is the board's now_ms(); differences are taken modulo 2^32, so the clock may wrap.
#pragma once

#include <cstdint>

#include <curvestep/core/error.hpp>
#include <curvestep/core/result.hpp>

namespace curvestep::firmware {

/// When the host was last heard, whether its silence was acted on, and the stall in progress.
class LinkWatch {
 public:
  /// A valid frame arrived at `now_ms`: a later silence is a new loss.
  void heard(std::uint32_t now_ms) noexcept {
    hold_latched_ = false;
    last_heard_ms_ = now_ms;
  }

  /// True the first time the link is found lost (`link_ok()` false) since the last valid frame;
  /// once acted on, `link_ok` is not asked again until then.
  template <class LinkOk>
  [[nodiscard]] bool newly_lost(LinkOk&& link_ok) noexcept {
    if (hold_latched_ || link_ok()) return false;
    hold_latched_ = true;
    return true;
  }

  /// A tick found the setpoint stream backed up; the first such tick starts the stall (board.now_ms()).
  template <class Clock>
  void stalled_tick(Clock& board) noexcept {
    if (!stalled_) stalled_since_ms_ = board.now_ms();
    stalled_ = true;
  }
  /// A tick advanced (or stands for a reason of its own): no stall.
  void stall_ended() noexcept { stalled_ = false; }
  /// True while the last tick found the setpoint stream backed up.
  [[nodiscard]] bool stalled() const noexcept { return stalled_; }

  /// True once the stall in progress has lasted `timeout_ms` (0: never) at `now_ms`; the stall then
  /// ends, so it is reported once.
  [[nodiscard]] bool stall_expired(std::uint32_t now_ms, std::uint32_t timeout_ms) noexcept {
    if (!stalled_ || timeout_ms == 0) return false;
    if (now_ms - stalled_since_ms_ < timeout_ms) return false;
    stalled_ = false;
    return true;
  }

  /// The fault of an expired stall (index = its length in ms): QueueUnderrun if the controller was
  /// `starved` (host-planned pieces not sent in time), else RetransmitLimit if the host was heard
  /// during the stall, else LinkTimeout.
  [[nodiscard]] Failure stall_fault(std::uint32_t now_ms, bool starved) const noexcept {
    const bool heard = static_cast<std::int32_t>(last_heard_ms_ - stalled_since_ms_) > 0;
    const Error code = starved ? Error::QueueUnderrun : (heard ? Error::RetransmitLimit : Error::LinkTimeout);
    return fail(code, now_ms - stalled_since_ms_);
  }

 private:
  std::uint32_t last_heard_ms_ = 0;     ///< when the last valid frame from the host arrived
  std::uint32_t stalled_since_ms_ = 0;  ///< the first tick of the stall in progress
  bool hold_latched_ = false;           ///< the link loss was acted on (until the next frame)
  bool stalled_ = false;                ///< the last tick found the setpoint stream backed up
};

}  // namespace curvestep::firmware
