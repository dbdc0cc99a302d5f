// SPDX-License-Identifier: MIT
// MachineOutputs: the machine-event outputs of the STM32 boards (firmware/board_hooks.hpp), the
// same pins and timers on the F1 and the F4 (docs/boards.md, "Machine outputs"):
//
//   spindle enable PB12, direction PB13 (high = counter-clockwise, M4), coolant mist PB14,
//   flood PB15, digital outputs 0..3 (M62-M65 P0..P3) PB8..PB11: push-pull outputs, one BSRR write;
//   spindle PWM TIM3 CH1 on PA6: 1 kHz, CCR1 = round(1000 x rpm / spindle_max_rpm), 0 when off;
//   servo pen TIM4 CH1 on PB6: 50 Hz (ARR 19999 at 1 MHz), CCR1 = the pulse width in µs that the
//   PenUp/PenDown event carries (the machine file's up_pulse_us / down_pulse_us).
//
// Every hook writes registers and returns; the state lives in the registers (no RAM). The timers'
// compare registers are preloaded (OCxPE), so a new width starts with the next period: a servo
// pulse or a PWM period is never cut short. Registers: RM0008 §15.4 (F1), RM0090 §18.4 (F4),
// the same offsets for CR1, EGR, CCMR1, CCER, PSC, ARR and CCR1, and the same TIM3/TIM4 addresses.
#pragma once

#include <cstdint>

#include <curvestep/boards/stm32/mmio.hpp>

#ifndef CURVESTEP_SPINDLE_MAX_RPM
#define CURVESTEP_SPINDLE_MAX_RPM 24000  // full-scale spindle speed: 100 % PWM duty (build setting)
#endif

namespace curvestep::stm32 {

/// Pins and timers of the machine outputs (the same on every STM32 board here).
struct MachineOutputPins {
  static constexpr std::uint32_t spindle_enable = 12;  ///< PB12
  static constexpr std::uint32_t spindle_ccw = 13;     ///< PB13
  static constexpr std::uint32_t coolant_mist = 14;    ///< PB14
  static constexpr std::uint32_t coolant_flood = 15;   ///< PB15
  static constexpr std::uint32_t first_output = 8;     ///< PB8: digital output 0
  static constexpr std::uint32_t output_count = 4;     ///< outputs 0..3 (PB8..PB11); higher numbers are ignored
  static constexpr std::uint32_t spindle_pwm_pin = 6;  ///< PA6 = TIM3_CH1
  static constexpr std::uint32_t servo_pin = 6;        ///< PB6 = TIM4_CH1
  static constexpr std::uintptr_t spindle_timer = 0x40000400;  ///< TIM3 (F1 and F4)
  static constexpr std::uintptr_t servo_timer = 0x40000800;    ///< TIM4 (F1 and F4)
  static constexpr std::uint32_t timer_hz = 1'000'000;         ///< both timers count microseconds
  static constexpr std::uint32_t spindle_pwm_period = 1000;    ///< counts: 1 kHz
  static constexpr std::uint32_t servo_period = 20000;         ///< counts: 20 ms, 50 Hz
  static constexpr std::uint32_t spindle_max_rpm = CURVESTEP_SPINDLE_MAX_RPM;  ///< rpm at 100 % duty
  static_assert(spindle_max_rpm > 0 && spindle_max_rpm <= 4'000'000, "CURVESTEP_SPINDLE_MAX_RPM: 1 .. 4 000 000");
};

/// Spindle PWM compare value for `rpm`: round(period x rpm / max_rpm), full scale at and above max_rpm.
[[nodiscard]] constexpr std::uint32_t spindle_duty_counts(std::uint32_t rpm) noexcept {
  using P = MachineOutputPins;
  if (rpm >= P::spindle_max_rpm) return P::spindle_pwm_period;
  return (rpm * P::spindle_pwm_period + P::spindle_max_rpm / 2) / P::spindle_max_rpm;  // < 2^32: rpm < 4e6
}

/// The outputs on GPIOB (`gpiob_bsrr`: its bit set/reset register) and TIM3/TIM4.
template <std::uintptr_t GpiobBsrr>
class MachineOutputs {
  using P = MachineOutputPins;

 public:
  /// Starts both PWM timers from their kernel clock `timer_clock_hz` with no output (duty 0, no
  /// servo pulse) and every output pin low. Pin modes and peripheral clocks are the Chip's.
  static void start(std::uint32_t timer_clock_hz) noexcept {
    reg(GpiobBsrr) = all_pins << 16;
    start_pwm(P::spindle_timer, timer_clock_hz, P::spindle_pwm_period);
    start_pwm(P::servo_timer, timer_clock_hz, P::servo_period);
  }

  /// Spindle: enable and direction pins, PWM duty from `rpm` (0 when off).
  static void spindle(bool on, bool counter_clockwise, std::uint32_t rpm) noexcept {
    reg(P::spindle_timer + ccr1) = on ? spindle_duty_counts(rpm) : 0;
    reg(GpiobBsrr) = level(P::spindle_enable, on) | level(P::spindle_ccw, counter_clockwise);
  }
  /// Coolant: mist and flood pins.
  static void coolant(bool mist, bool flood) noexcept {
    reg(GpiobBsrr) = level(P::coolant_mist, mist) | level(P::coolant_flood, flood);
  }
  /// Digital output `number` (M62-M65 P): numbers from output_count on are not wired and ignored.
  static void digital_output(std::uint32_t number, bool on) noexcept {
    if (number < P::output_count) reg(GpiobBsrr) = level(P::first_output + number, on);
  }
  /// Servo pen: pulses of `pulse_us` from the next 20 ms period on; 0 (a pen without a servo
  /// width, e.g. a z pen's event) leaves the servo as it is.
  static void pen(std::uint32_t pulse_us) noexcept {
    if (pulse_us != 0 && pulse_us < P::servo_period) reg(P::servo_timer + ccr1) = pulse_us;
  }

 private:
  static constexpr std::uintptr_t cr1 = 0x00, egr = 0x14, ccmr1 = 0x18, ccer = 0x20, psc = 0x28, arr = 0x2C, ccr1 = 0x34;
  static constexpr std::uint32_t all_pins = (1u << P::spindle_enable) | (1u << P::spindle_ccw) | (1u << P::coolant_mist) |
                                            (1u << P::coolant_flood) | (((1u << P::output_count) - 1) << P::first_output);

  /// The BSRR bit that drives `pin` to `high`.
  static constexpr std::uint32_t level(std::uint32_t pin, bool high) noexcept { return high ? 1u << pin : 1u << (pin + 16); }

  /// Channel 1 in PWM mode 1 (high while CNT < CCR1) with CCR1 and ARR preloaded, counting at 1 MHz.
  static void start_pwm(std::uintptr_t timer, std::uint32_t timer_clock_hz, std::uint32_t period) noexcept {
    reg(timer + cr1) = 0;
    reg(timer + psc) = timer_clock_hz / P::timer_hz - 1;
    reg(timer + arr) = period - 1;
    reg(timer + ccr1) = 0;
    reg(timer + ccmr1) = (0b110u << 4) | (1u << 3);  // OC1M = PWM mode 1, OC1PE
    reg(timer + ccer) = 1u;                          // CC1E, active high
    reg(timer + egr) = 1u;                           // UG: load PSC, ARR and CCR1 now
    reg(timer + cr1) = (1u << 7) | 1u;               // ARPE, CEN
  }
};

}  // namespace curvestep::stm32
