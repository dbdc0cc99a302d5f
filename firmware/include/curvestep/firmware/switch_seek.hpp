// SPDX-License-Identifier: MIT
// SwitchSeek: the App's homing seek (SeekSwitch, docs/firmware.md "Homing").
//
// SeekSwitch arms one limit switch for the next job; while armed, that switch closing ends the job
// where it stands (seek_closed in limit_switches.hpp; not a fault, whichever way the axis moved),
// and the App reports where it stopped once (SwitchReport). A job that ends without meeting its
// switch, Abort and a new session disarm it.
#pragma once

#include <cstddef>
#include <cstdint>

#include <curvestep/firmware/limit_switches.hpp>
#include <curvestep/protocol/messages.hpp>

namespace curvestep::firmware {

/// The switch that ends the next job, and where the last seek stopped.
class SwitchSeek {
 public:
  /// Arms `limit_switch` (limit_switch_bit) for the next job; false (nothing armed) for a switch
  /// of an axis beyond `axis_count` (2 per axis: min, max).
  [[nodiscard]] bool arm(std::uint8_t limit_switch, std::size_t axis_count) noexcept {
    if (limit_switch >= 2 * axis_count) return false;
    switch_ = limit_switch;
    return true;
  }
  /// No switch ends the next job.
  void disarm() noexcept { switch_ = no_limit_switch; }
  /// True if the armed switch is among the `closed` ones (limit_switches()).
  [[nodiscard]] bool met(std::uint8_t closed) const noexcept { return seek_closed(closed, switch_); }

  /// Notes where the job met the armed switch (the setpoint's index and position) for the report.
  void record_stop(std::uint32_t setpoint_index, const protocol::WirePoint& at) noexcept {
    report_ = protocol::SwitchReport{switch_, setpoint_index, at[0], at[1], at[2]};
  }
  /// The SwitchReport of the last seek that met its switch.
  [[nodiscard]] const protocol::SwitchReport& report() const noexcept { return report_; }

 private:
  protocol::SwitchReport report_{};      ///< where the last seek stopped, reported once
  std::uint8_t switch_ = no_limit_switch;  ///< the armed switch (limit_switch_bit), or none
};

}  // namespace curvestep::firmware
