// SPDX-License-Identifier: MIT
// MachineOutputs: the host board's machine-event outputs (firmware/board_hooks.hpp) on output
// lines named in the machine file's "gpio" section (docs/host_board.md, "Machine outputs"):
// spindle enable and direction (high = counter-clockwise, M4), coolant mist and flood, digital
// outputs 0..N-1 (M62-M65 P), and a servo pen's 50 Hz signal in software (ServoPulseTrain, its
// own thread). A hook sets a line and returns; the pen hook only hands the width to the pulse
// train. Numbers of digital outputs that are not wired are counted and ignored (`curvestep gpio`
// refuses such a job before it starts).
//
// Lines: set(std::size_t line, bool high) with the line indices below (GpiodLineSet on libgpiod,
// or a recording stand-in in tests), callable from two threads (the tick and the servo).
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <curvestep/boards/host/servo_pulse_train.hpp>

namespace curvestep::boards::host {

/// Names of the machine-output lines on one chip (empty: not wired).
struct MachineOutputLines {
  std::string chip;                  ///< as GpioLines::chip
  std::string spindle_enable;        ///< high while the spindle turns
  std::string spindle_direction;     ///< high for counter-clockwise (M4)
  std::string coolant_mist;          ///< M7
  std::string coolant_flood;         ///< M8
  std::string servo;                 ///< a servo pen's signal (50 Hz software PWM)
  std::vector<std::string> outputs;  ///< digital outputs 0, 1, ... (M62-M65 P)

  /// True if any line is named.
  [[nodiscard]] bool any() const noexcept {
    return !spindle_enable.empty() || !spindle_direction.empty() || !coolant_mist.empty() || !coolant_flood.empty() ||
           !servo.empty() || !outputs.empty();
  }
};

/// Line indices of a line set made from MachineOutputLines (the order of output_line_roles()).
inline constexpr std::size_t spindle_enable_line = 0, spindle_direction_line = 1, coolant_mist_line = 2,
                             coolant_flood_line = 3, servo_line = 4, first_digital_output_line = 5;

/// Every line of `lines` in index order: its name (empty: not wired) and its role for messages
/// ("spindle enable", "digital output 2", ...).
[[nodiscard]] inline std::vector<std::pair<std::string, std::string>> output_line_roles(const MachineOutputLines& lines) {
  std::vector<std::pair<std::string, std::string>> roles{{lines.spindle_enable, "spindle enable"},
                                                         {lines.spindle_direction, "spindle direction"},
                                                         {lines.coolant_mist, "coolant mist"},
                                                         {lines.coolant_flood, "coolant flood"},
                                                         {lines.servo, "servo pen"}};
  for (std::size_t k = 0; k < lines.outputs.size(); ++k) roles.emplace_back(lines.outputs[k], "digital output " + std::to_string(k));
  return roles;
}

/// The machine event hooks HostBoard forwards to (DeviceOptions::machine_outputs).
class MachineOutputHooks {
 public:
  virtual ~MachineOutputHooks() = default;
  /// Spindle state after M3/M4/M5/S.
  virtual void spindle(bool on, bool counter_clockwise, std::uint32_t rpm) noexcept = 0;
  /// Coolant state after M7/M8/M9.
  virtual void coolant(bool mist, bool flood) noexcept = 0;
  /// M62-M65: digital output `number` on or off.
  virtual void digital_output(std::uint32_t number, bool on) noexcept = 0;
  /// Pen up/down; `pulse_us` the servo's width (0: none given).
  virtual void pen(bool down, std::uint32_t pulse_us) noexcept = 0;
};

/// The hooks on `Lines`, with a servo pulse train thread when a servo line is wired.
template <class Lines, class Clock = MonotonicClock>
class MachineOutputs final : public MachineOutputHooks {
 public:
  /// Outputs on `lines` with `digital_outputs` digital outputs; `servo`: run the pulse train.
  MachineOutputs(Lines& lines, std::size_t digital_outputs, bool servo, Clock clock = Clock{})
      : lines_(lines), digital_outputs_(digital_outputs), train_(lines, servo_line, clock) {
    if (servo) servo_thread_ = std::thread([this] { train_.run(stop_); });
  }
  /// Stops the pulse train (its line ends low).
  ~MachineOutputs() override {
    stop_.store(true);
    if (servo_thread_.joinable()) servo_thread_.join();
  }
  MachineOutputs(const MachineOutputs&) = delete;
  MachineOutputs& operator=(const MachineOutputs&) = delete;

  void spindle(bool on, bool counter_clockwise, std::uint32_t) noexcept override {
    lines_.set(spindle_direction_line, counter_clockwise);
    lines_.set(spindle_enable_line, on);
  }
  void coolant(bool mist, bool flood) noexcept override {
    lines_.set(coolant_mist_line, mist);
    lines_.set(coolant_flood_line, flood);
  }
  void digital_output(std::uint32_t number, bool on) noexcept override {
    if (number < digital_outputs_) lines_.set(first_digital_output_line + number, on);
    else unwired_outputs_.fetch_add(1, std::memory_order_relaxed);
  }
  void pen(bool, std::uint32_t pulse_us) noexcept override {
    if (pulse_us != 0) train_.set_pulse_us(pulse_us);
  }

  /// Digital-output events whose number has no line (ignored).
  [[nodiscard]] std::size_t unwired_outputs() const noexcept { return unwired_outputs_.load(std::memory_order_relaxed); }
  /// The servo's pulse width in force, µs (0: no pulses yet).
  [[nodiscard]] std::uint32_t servo_pulse_us() const noexcept { return train_.pulse_us(); }

 private:
  Lines& lines_;
  std::size_t digital_outputs_;
  ServoPulseTrain<Lines, Clock> train_;
  std::atomic<bool> stop_{false};
  std::atomic<std::size_t> unwired_outputs_{0};
  std::thread servo_thread_;  // last: started once every other member exists
};

}  // namespace curvestep::boards::host
