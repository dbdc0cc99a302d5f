// SPDX-License-Identifier: MIT
// The controller's setpoint stream as an upload receives it: each setpoint becomes a SetpointRecord
// as it arrives (time from its index, position from its raw Q16.16, speed from the previous
// setpoint when they are consecutive) and goes to a sink, or into a vector when there is none.
// With a sink nothing is kept: memory independent of the job's length (`stream --capture`).
//
// The link delivers batches in order; ticks the controller stood held or starved are skipped
// indices. A setpoint whose index is not above the last one received is counted as duplicated
// and dropped.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <curvestep/host/simulator.hpp>
#include <curvestep/protocol/messages.hpp>

namespace curvestep::host::link {

class SetpointCapture {
 public:
  /// `sink` may be empty: then the records are kept (records()).
  explicit SetpointCapture(SetpointSink sink = {}) : sink_(std::move(sink)) {}

  /// The controller's control rate (records' time and speed); set before the first setpoint.
  void set_rate_hz(double rate_hz) noexcept { rate_hz_ = rate_hz; }

  /// One setpoint of a SetpointBatch.
  void receive(std::uint32_t index, const protocol::WirePoint& point);

  [[nodiscard]] std::size_t received() const noexcept { return received_; }
  [[nodiscard]] std::size_t duplicates() const noexcept { return duplicates_; }
  [[nodiscard]] bool empty() const noexcept { return received_ == 0; }
  /// The highest index received (0 when empty).
  [[nodiscard]] std::uint32_t last_index() const noexcept { return last_index_; }
  /// The last index of the first run of consecutive indices (0 when empty).
  [[nodiscard]] std::uint32_t first_run_end() const noexcept { return first_run_end_; }
  /// Indices skipped between the first setpoint and `end_index` (the controller's setpoint index at
  /// the end): ticks it stood held or starved.
  [[nodiscard]] std::size_t standing_ticks(std::uint32_t end_index) const noexcept;
  /// The first run of skipped indices that starts at or after index `from` and ends before `until`
  /// (the ticks a resumed hold stood still); 0 if there is none.
  [[nodiscard]] std::uint64_t first_gap_between(std::uint64_t from, std::uint64_t until) const noexcept;
  /// The records kept when there is no sink.
  [[nodiscard]] std::vector<SetpointRecord>& records() noexcept { return records_; }

 private:
  SetpointSink sink_;
  double rate_hz_ = 1000;
  std::vector<SetpointRecord> records_;
  protocol::WirePoint previous_{};
  std::size_t received_ = 0;
  std::size_t duplicates_ = 0;
  std::size_t skipped_ = 0;
  std::uint32_t last_index_ = 0;
  std::uint32_t first_run_end_ = 0;
  bool gap_seen_ = false;
  /// Each run of skipped indices: the index received before it and its length (a few per hold or stall).
  struct Gap {
    std::uint32_t after = 0;
    std::uint32_t length = 0;
  };
  std::vector<Gap> gaps_;
};

}  // namespace curvestep::host::link
