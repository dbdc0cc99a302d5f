// SPDX-License-Identifier: MIT
// The App's run-time settings, its counters and the sizes it takes from the board.
#pragma once

#include <cstddef>
#include <cstdint>

#include <curvestep/core/motion/cusps.hpp>
#include <curvestep/protocol/frame.hpp>
#include <curvestep/protocol/messages.hpp>

namespace curvestep::firmware {

/// Run-time settings of the App (link timing, streaming).
struct AppSettings {
  std::uint32_t link_timeout_ms = 1000;  ///< no valid frame for this long while connected: feed hold (0: never)
  std::uint32_t ack_interval_ms = 250;   ///< heartbeat Ack period while connected (0: none)
  bool stream_setpoints = true;          ///< send SetpointBatch messages while moving
  std::uint32_t stall_timeout_ms = 1000; ///< setpoint stream backed up this long while moving: Fault (0: wait for ever)
  std::uint32_t retransmit_timeout_ms = 100;  ///< resend unacknowledged setpoint batches after this silence
  bool watch_ticks = true;               ///< time every tick on the board's cycle clock, if it has one (off: ticks not paced by a clock)
  std::uint32_t tick_deadline_periods = 1;  ///< a tick starting more than this many periods late is a Fault (TickDeadlineMissed); 0: count overruns only
};

/// Counters of the App's link work (nothing is dropped that matters: see each field).
struct AppStatistics {
  std::uint32_t dropped_frames = 0;     ///< unsequenced frames (Acks, reports) that found the transmit buffer full
  std::uint32_t dropped_setpoints = 0;  ///< always 0 since protocol version 2 (kept for the API)
  std::uint32_t stalled_ticks = 0;      ///< ticks that did not advance because the setpoint stream was backed up
  std::uint32_t setpoint_go_backs = 0;  ///< retransmission rounds of the setpoint stream
  std::uint16_t max_queue_depth = 0;    ///< deepest the segment queue has been this session
};

/// Frames of the board's setpoint window: B::setpoint_window if the board says, else 4.
template <class B>
[[nodiscard]] constexpr std::size_t board_setpoint_window() noexcept {
  if constexpr (requires { B::setpoint_window; }) {
    return static_cast<std::size_t>(B::setpoint_window);
  } else {
    return 4;
  }
}
/// Smallest setpoint batch the App shrinks to on a noisy line.
inline constexpr std::size_t min_setpoints_per_batch = 4;
/// Transmit-buffer bytes kept free of setpoint frames, for Acks and reports.
inline constexpr std::size_t transmit_reserve_bytes = 64;

/// Bytes of the transmit buffer (three largest frames).
inline constexpr std::size_t transmit_buffer_bytes = 3 * protocol::max_encoded_frame_size;
/// Setpoints buffered for SetpointBatch messages: B::setpoint_buffer if the board says (at least
/// one full batch), else two batches.
template <class B>
[[nodiscard]] constexpr std::size_t board_setpoint_buffer() noexcept {
  if constexpr (requires { B::setpoint_buffer; }) {
    static_assert(B::setpoint_buffer >= protocol::max_setpoints_per_batch, "the setpoint buffer must hold a full batch");
    return static_cast<std::size_t>(B::setpoint_buffer);
  } else {
    return 2 * protocol::max_setpoints_per_batch;
  }
}
/// Queue slots one wire segment may need (a Bézier split at every cusp the planner finds).
inline constexpr std::size_t slots_per_segment = CuspList<>::capacity + 1;

}  // namespace curvestep::firmware
