// SPDX-License-Identifier: MIT
// FeedOverrideCommand: the App's side of FeedOverride (0x19). It checks the percentages, hands them
// to the planner (MotionController::set_override, which lets them take effect at its next point of
// zero acceleration) and remembers what the StatusReport says of them: the values last set and the
// setpoint index they were set before (the planner's tick then), which is what
// `curvestep sim --override-at` needs to replay the device bit for bit. A new session starts at
// 100 % (reset).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include <curvestep/core/motion/feed_override.hpp>
#include <curvestep/core/result.hpp>
#include <curvestep/protocol/messages.hpp>

namespace curvestep::firmware {

/// The override last set on a controller with a planner, for its StatusReport.
class FeedOverrideCommand {
 public:
  /// Decodes a FeedOverride payload and sets it on `controller` (before its next setpoint).
  /// BadPayload for a malformed payload; InvalidArgument at byte 0 for a feed outside 10..200 %,
  /// at byte 2 for a rapid override outside 10..100 %.
  template <class Controller>
  [[nodiscard]] Result<void> take(std::span<const std::byte> payload, Controller& controller) noexcept {
    CURVESTEP_TRY(const protocol::FeedOverride m, protocol::decode<protocol::FeedOverride>(payload));
    if (m.feed_percent < FeedOverride::min_feed_percent || m.feed_percent > FeedOverride::max_feed_percent) {
      return fail(Error::InvalidArgument, 0);
    }
    if (m.rapid_percent < FeedOverride::min_rapid_percent || m.rapid_percent > FeedOverride::max_rapid_percent) {
      return fail(Error::InvalidArgument, 2);
    }
    CURVESTEP_CHECK(controller.set_override(FeedOverride{m.feed_percent, m.rapid_percent}));
    last_ = m;
    index_ = static_cast<std::uint32_t>(controller.tick());
    return ok();
  }

  /// Back to 100 % (a new session): on the stopped `controller` at once.
  template <class Controller>
  void reset(Controller& controller) noexcept {
    *this = FeedOverrideCommand{};
    (void)controller.set_override(FeedOverride{});  // valid values: cannot fail
  }

  /// Fills the StatusReport's override fields.
  void describe(protocol::StatusReport& status) const noexcept {
    status.feed_override_percent = last_.feed_percent;
    status.rapid_override_percent = last_.rapid_percent;
    status.override_index = index_;
  }

 private:
  protocol::FeedOverride last_{};
  std::uint32_t index_ = 0;
};

/// A controller without a planner has no override (FeedOverride is NotSupported): its StatusReport
/// keeps the defaults, and no RAM is spent.
struct NoFeedOverride {
  void describe(protocol::StatusReport&) const noexcept {}
};

}  // namespace curvestep::firmware
