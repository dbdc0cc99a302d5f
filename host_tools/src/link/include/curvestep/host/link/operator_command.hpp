// SPDX-License-Identifier: MIT
// OperatorCommand: what the operator asks of a running job (keys, signals), as stream_job takes it.
#pragma once

#include <cstdint>

#include <curvestep/core/motion/feed_override.hpp>

namespace curvestep::host::link {

/// One request from the operator (grbl's real-time commands: `!` hold, `~` resume, Ctrl-X abort,
/// `?` status, and its feed and rapid override commands).
enum class OperatorCommand : std::uint8_t {
  None,          ///< nothing asked
  Hold,          ///< feed hold: brake to a stop on the path (FeedHold)
  Resume,        ///< continue after a hold (Resume)
  Abort,         ///< stop at once and end the job (Abort)
  Status,        ///< print one status line
  FeedPlus10,    ///< feed override + 10 % (at most 200 %)
  FeedMinus10,   ///< feed override − 10 % (at least 10 %)
  FeedPlus1,     ///< feed override + 1 %
  FeedMinus1,    ///< feed override − 1 %
  FeedReset,     ///< feed override 100 %
  RapidFull,     ///< rapid override 100 %
  RapidHalf,     ///< rapid override 50 %
  RapidQuarter,  ///< rapid override 25 %
};

/// True for the commands that change the feed or rapid override.
[[nodiscard]] constexpr bool changes_override(OperatorCommand c) noexcept {
  return c >= OperatorCommand::FeedPlus10 && c <= OperatorCommand::RapidQuarter;
}

/// `current` changed by override command `c`, kept inside FeedOverride's ranges (grbl's rule:
/// a step past the end stops at the end).
[[nodiscard]] constexpr FeedOverride adjusted_override(FeedOverride current, OperatorCommand c) noexcept {
  int feed = current.feed_percent;
  switch (c) {
    case OperatorCommand::FeedPlus10: feed += 10; break;
    case OperatorCommand::FeedMinus10: feed -= 10; break;
    case OperatorCommand::FeedPlus1: feed += 1; break;
    case OperatorCommand::FeedMinus1: feed -= 1; break;
    case OperatorCommand::FeedReset: feed = 100; break;
    case OperatorCommand::RapidFull: current.rapid_percent = 100; break;
    case OperatorCommand::RapidHalf: current.rapid_percent = 50; break;
    case OperatorCommand::RapidQuarter: current.rapid_percent = 25; break;
    default: break;
  }
  if (feed < FeedOverride::min_feed_percent) feed = FeedOverride::min_feed_percent;
  if (feed > FeedOverride::max_feed_percent) feed = FeedOverride::max_feed_percent;
  current.feed_percent = static_cast<std::uint16_t>(feed);
  return current;
}

}  // namespace curvestep::host::link
