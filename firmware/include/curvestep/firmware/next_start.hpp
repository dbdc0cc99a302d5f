// SPDX-License-Identifier: MIT
// NextStart: where the App's next segment must start (SegmentsNotConnected otherwise).
//
// Within a job, the end of the last queued segment or piece; between jobs, where the machine
// stands: where the last job ended, where an Abort, a fault or a homing switch stopped it, or the
// coordinates SetPosition gave it. Unknown after power-up, a new session or a new configuration:
// the first job then declares the position (docs/firmware.md, "What a host must do").
#pragma once

#include <curvestep/protocol/messages.hpp>

namespace curvestep::firmware {

/// The wire point the next segment must start at, if one is required.
class NextStart {
 public:
  /// True if a start point is required (known()), so a segment must begin there.
  [[nodiscard]] bool known() const noexcept { return known_; }
  /// True if a segment starting at `start` connects: at the required point, or none is required.
  [[nodiscard]] bool connects(const protocol::WirePoint& start) const noexcept { return !known_ || start == at_; }

  /// The next segment must start at `at`.
  void set(const protocol::WirePoint& at) noexcept {
    at_ = at;
    known_ = true;
  }
  /// Between jobs: the machine stands at `position`, required if `positioned` (the step
  /// generator knows where the machine is), else the next job declares it.
  void stand_at(const protocol::WirePoint& position, bool positioned) noexcept {
    known_ = positioned;
    at_ = position;
  }
  /// No start is required: the next job declares the position.
  void forget() noexcept { known_ = false; }

 private:
  protocol::WirePoint at_{};  ///< the required start (Q16.16 raw)
  bool known_ = false;        ///< a start is required
};

}  // namespace curvestep::firmware
