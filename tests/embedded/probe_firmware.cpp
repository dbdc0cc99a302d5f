// SPDX-License-Identifier: MIT
// Probe: the firmware App<Board> (link, queue, planner, steps) for Q16.16 and float setpoints.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include <curvestep/firmware/app.hpp>
#include <curvestep/protocol/frame.hpp>

#include "probe.hpp"

namespace curvestep::probe {
namespace {

/// A board whose serial input is a fixed script and whose outputs go to `sink`.
class ProbeBoard {
 public:
  static constexpr std::uint8_t axis_count = 3;
  static constexpr std::size_t step_events_per_tick = 64;
  static constexpr StepTiming step_timing() { return StepTiming{}; }

  std::uint32_t now_ms() { return clock_ms++; }
  std::size_t read(std::span<std::byte> into) {
    std::size_t n = 0;
    while (n < into.size() && position < script_size) into[n++] = script[position++];
    return n;
  }
  std::size_t write(std::span<const std::byte> bytes) {
    sink = sink + static_cast<std::int32_t>(bytes.size());
    return bytes.size();
  }
  void set_direction(std::uint64_t time_ticks, std::uint8_t axis, bool positive) {
    sink = sink + static_cast<std::int32_t>(time_ticks & 0xFFu) + axis + (positive ? 1 : 0);
  }
  void set_step(std::uint64_t time_ticks, std::uint8_t axis, bool high) {
    sink = sink + static_cast<std::int32_t>(time_ticks & 0xFFu) + axis + (high ? 1 : 0);
  }
  void fault_stop() { sink = sink + 1; }

  std::array<std::byte, 512> script{};
  std::size_t script_size = 0;
  std::size_t position = 0;
  std::uint32_t clock_ms = 0;

  void append(const protocol::Message& m, std::uint8_t sequence) {
    const auto size = protocol::encode_frame(m, sequence, std::span<std::byte>(script).subspan(script_size));
    if (size) script_size += size.value();
  }
};

static_assert(firmware::Board<ProbeBoard>);

template <Scalar S>
void exercise_app(std::int32_t scale) {
  ProbeBoard board;
  board.append(protocol::Message(protocol::Hello{protocol::protocol_version, 7}), 0);
  protocol::MachineConfiguration config;
  config.max_velocity_mm_per_s = 100;
  config.max_acceleration_mm_per_s2 = 1000;
  config.max_jerk_mm_per_s3 = 10000;
  config.default_feed_mm_per_s = 50 << 16;
  config.tolerance_mm = 0.01;
  config.junction_deviation_mm = 0.05;
  config.max_step_rate_hz = 100000;
  config.control_rate_hz = 1000;
  for (auto& axis : config.axes) axis.steps_per_mm = 80;
  board.append(protocol::Message(config), 0);
  protocol::QueueSegment segment;
  segment.axis_count = 3;
  segment.points[1] = protocol::WirePoint{scale << 16, 0, 0};
  segment.end_of_job = true;
  board.append(protocol::Message(segment), 1);
  board.append(protocol::Message(protocol::Start{}), 2);
  firmware::App<ProbeBoard, S, 16, 8> app(board);
  for (int i = 0; i < 2000; ++i) {
    app.poll();
    app.on_tick();
  }
  sink = sink + app.position()[0] + static_cast<std::int32_t>(sizeof(app));
}

}  // namespace

void probe_firmware() {
  exercise_app<Q16_16>(5 + (sink & 1));
  exercise_app<float>(5 + (sink & 1));
}

}  // namespace curvestep::probe
