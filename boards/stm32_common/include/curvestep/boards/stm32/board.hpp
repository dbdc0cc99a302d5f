// SPDX-License-Identifier: MIT
// stm32::Board<Chip>: the part of the STM32 boards that does not depend on the chip — the console
// on USART1 (interrupt driven, usart.hpp), SysTick, the step/dir pins on GPIOA (STEP X/Y/Z =
// PA0/PA1/PA2, DIR X/Y/Z = PA3/PA4/PA5, one BSRR write each) and the TIM2 edge player
// (step_edges.hpp), the machine outputs (spindle, coolant, digital outputs, servo pen on GPIOB,
// TIM3 and TIM4: machine_outputs.hpp) with the bring-up monitor's interface and the
// firmware::Board concept with its machine event hooks (firmware/board_hooks.hpp).
//
// The chip supplies (boards/stm32f1/board.hpp, boards/stm32f4/board.hpp):
//   using Scalar; name; hse_hz; target_hclk_hz        setpoint scalar and clock targets
//   usart1, usart1_irq, gpioa_bsrr, gpiob_bsrr         addresses (reference manual memory map)
//   step_events_per_tick, edge_ring                    StepBatch and edge ring capacities
//   fallback_clocks                                    the clocks before init() (HSI)
//   static Clocks setup_clocks() noexcept              clock tree, bounded waits, emulator detection
//   static void setup_gpio() noexcept                  peripheral clocks, pin modes, USART1 pins,
//                                                      the machine outputs' pins and TIM3/TIM4 clocks
//   static void enable_step_timer() noexcept           TIM2 clock on
// and its board.cpp routes USART1_IRQHandler, TIM2_IRQHandler and curvestep_board_fault_putc to
// on_usart_interrupt(), on_step_timer_interrupt() and fault_putc().
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include <curvestep/boards/stm32/clocks.hpp>
#include <curvestep/boards/stm32/cycle_counter.hpp>
#include <curvestep/boards/stm32/machine_outputs.hpp>
#include <curvestep/boards/stm32/mmio.hpp>
#include <curvestep/boards/stm32/startup.hpp>
#include <curvestep/boards/stm32/step_edges.hpp>
#include <curvestep/boards/stm32/usart.hpp>
#include <curvestep/core/motion/step_generator.hpp>

namespace curvestep::stm32 {

/// An STM32 board: console, tick, step/dir GPIO and timed edges, for the chip `Chip` (above).
template <class Chip>
class Board {
 public:
  using Scalar = typename Chip::Scalar;                           ///< setpoint scalar
  static constexpr const char* name = Chip::name;                 ///< board name in reports
  static constexpr std::size_t axes = 3;                          ///< step/dir channels
  static constexpr std::uint32_t baud = 115200;                   ///< console baud rate
  static constexpr std::size_t console_buffer = 256;              ///< bytes in the console's receive ring
  static constexpr std::size_t console_tx_buffer = Chip::console_tx_buffer;  ///< bytes in its transmit ring
  static constexpr std::uint32_t hse_hz = Chip::hse_hz;           ///< crystal
  static constexpr std::uint32_t target_hclk_hz = Chip::target_hclk_hz;  ///< PLL target

  /// Clocks (HSE -> PLL, or the HSI fallback), GPIO, USART1 with its interrupt, and the machine
  /// outputs off (pins low, no spindle PWM, no servo pulse).
  Clocks init() noexcept {
    clocks_ = Chip::setup_clocks();
    Chip::setup_gpio();
    Outputs::start(apb1_timer_clock());
    console_.start(clocks_.pclk2_hz, baud, 0x20);
    if (!clocks_.emulated) start_cycle_counter();  // QEMU 7.2 models no DWT
    enable_interrupts();
    return clocks_;
  }

  /// Queues console bytes; returns how many fitted in the transmit ring.
  std::size_t write(std::span<const std::uint8_t> bytes) noexcept { return console_.write(bytes); }
  /// Queues every byte, waiting for room.
  void write_all(std::span<const std::uint8_t> bytes) noexcept { console_.write_all(bytes); }
  /// Takes one received console byte; false when none.
  bool read(std::uint8_t& byte) noexcept { return console_.read(byte); }
  /// Room in the transmit ring.
  [[nodiscard]] std::size_t writable() const noexcept { return console_.writable(); }
  /// Received bytes lost to a full ring or a hardware overrun.
  [[nodiscard]] std::uint32_t receive_overruns() const noexcept { return console_.receive_overruns(); }

  /// Starts the control tick: `callback(context)` from the SysTick interrupt `rate_hz` times a second.
  bool start_tick(std::uint32_t rate_hz, void (*callback)(void*), void* context) noexcept {
    return start_systick(clocks_.hclk_hz, rate_hz, callback, context);
  }
  /// Ticks since start_tick().
  [[nodiscard]] std::uint32_t ticks() const noexcept { return systick_count(); }

  /// Drives the DIR lines: bit a of `positive_mask` set = axis a moves in the positive direction.
  void set_directions(std::uint32_t positive_mask) noexcept {
    const std::uint32_t set = pin_bits(dir_pins, positive_mask);
    const std::uint32_t clear = pin_bits(dir_pins, ~positive_mask & 0b111u);
    reg(Chip::gpioa_bsrr) = set | (clear << 16);
  }
  /// Raises the STEP lines of the axes in `mask` (one BSRR write).
  void raise_steps(std::uint32_t mask) noexcept { reg(Chip::gpioa_bsrr) = pin_bits(step_pins, mask); }
  /// Lowers the STEP lines of the axes in `mask` (one BSRR write).
  void lower_steps(std::uint32_t mask) noexcept { reg(Chip::gpioa_bsrr) = pin_bits(step_pins, mask) << 16; }

  // --- the firmware::Board concept (firmware/include/curvestep/firmware/board.hpp) ---
  static constexpr std::uint8_t axis_count = 3;                                     ///< driven axes
  static constexpr std::size_t step_events_per_tick = Chip::step_events_per_tick;  ///< StepBatch capacity per control tick
  static constexpr std::size_t edge_ring = Chip::edge_ring;  ///< timed edges waiting for TIM2 (two ticks)
  static constexpr std::size_t setpoint_window = Chip::setpoint_window;  ///< setpoint frames in flight (firmware::App)
  static constexpr std::size_t setpoint_buffer = Chip::setpoint_buffer;  ///< setpoints waiting for a batch (firmware::App)
  // Edges of tick k are played during tick k + 1 while tick k + 1's are queued: a ring of two
  // full ticks never overflows while TIM2 keeps up (a full ring is a StepsLost fault).
  static_assert(edge_ring >= 2 * step_events_per_tick, "the edge ring must hold two ticks of edges");
  /// 1 MHz step timer (TIM2), 2 µs pulses and gaps, 1 µs direction set-up and hold.
  static constexpr StepTiming step_timing() noexcept { return StepTiming{1'000'000, 2000, 2000, 1000, 1000}; }
  /// Milliseconds since init() (from SysTick, whatever its rate).
  [[nodiscard]] std::uint32_t now_ms() const noexcept { return systick_milliseconds(); }
  /// Received bytes into `into`; never blocks.
  std::size_t read(std::span<std::byte> into) noexcept {
    std::size_t count = 0;
    std::uint8_t byte = 0;
    while (count < into.size() && console_.read(byte)) into[count++] = static_cast<std::byte>(byte);
    return count;
  }
  /// Queues what fits of `bytes` for transmission; never blocks.
  std::size_t write(std::span<const std::byte> bytes) noexcept {
    return console_.write(std::span(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()));
  }
  /// Queues a DIR edge at step-timer time `time_ticks` (played one control period later).
  void set_direction(std::uint64_t time_ticks, std::uint8_t axis, bool positive) noexcept {
    edges_.push(time_ticks, axis, true, positive);
  }
  /// Queues a STEP edge at step-timer time `time_ticks` (played one control period later).
  void set_step(std::uint64_t time_ticks, std::uint8_t axis, bool high) noexcept { edges_.push(time_ticks, axis, false, high); }
  /// Drops every queued edge and lowers the STEP lines.
  void fault_stop() noexcept { edges_.stop(); }
  /// Starts TIM2 for the edges of a control tick of `control_rate_hz`.
  void start_steps(std::uint32_t control_rate_hz) noexcept {
    Chip::enable_step_timer();
    barrier();
    const std::uint32_t timer_hz = step_timing().timer_hz;
    edges_.start(apb1_timer_clock(), timer_hz, control_rate_hz == 0 ? timer_hz / 1000 : timer_hz / control_rate_hz,
                 step_pin_numbers, dir_pin_numbers, clocks_.emulated);
  }
  /// Processor clocks, free running (wraps at 2^32): DWT CYCCNT, or in an emulator SysTick's
  /// count and counter (QEMU with -icount: instructions). The App times its ticks with it.
  [[nodiscard]] std::uint32_t cycle_count() const noexcept { return clocks_.emulated ? systick_cycles() : cycle_counter(); }
  /// Clocks of cycle_count() per second (HCLK).
  [[nodiscard]] std::uint32_t cycles_per_second() const noexcept { return clocks_.hclk_hz; }
  /// Edges lost to a full edge ring (App faults with StepsLost when this grows; 0 in an emulator).
  [[nodiscard]] std::uint32_t edges_dropped() const noexcept { return edges_.edges_dropped(); }

  // --- machine event hooks (firmware/board_hooks.hpp; pins and timers: machine_outputs.hpp) ---
  /// Spindle enable/direction pins and PWM duty (rpm / CURVESTEP_SPINDLE_MAX_RPM).
  void spindle(bool on, bool counter_clockwise, std::uint32_t rpm, std::uint32_t) noexcept {
    Outputs::spindle(on, counter_clockwise, rpm);
  }
  /// Coolant mist and flood pins.
  void coolant(bool mist, bool flood, std::uint32_t) noexcept { Outputs::coolant(mist, flood); }
  /// Digital outputs 0..3 (M62-M65); higher numbers are ignored.
  void digital_output(std::uint32_t number, bool on, std::uint32_t) noexcept { Outputs::digital_output(number, on); }
  /// Servo pen pulse width (µs, from the event; 0 leaves the servo as it is).
  void pen(bool, std::uint32_t pulse_us, std::uint32_t) noexcept { Outputs::pen(pulse_us); }

  /// Clocks measured by init().
  [[nodiscard]] const Clocks& clocks() const noexcept { return clocks_; }

  // --- for the chip's interrupt handlers (board.cpp) ---
  /// USART1_IRQHandler.
  static void on_usart_interrupt() noexcept { console_.on_interrupt(); }
  /// TIM2_IRQHandler.
  static void on_step_timer_interrupt() noexcept { edges_.on_interrupt(); }
  /// curvestep_board_fault_putc: one character written by polling (fault reports).
  static void fault_putc(char c) noexcept { Console::write_polled(static_cast<std::uint8_t>(c)); }

 private:
  using Console = Usart<Chip::usart1, Chip::usart1_irq, console_buffer, console_tx_buffer>;
  using Edges = StepEdges<0x40000000, Chip::gpioa_bsrr, Chip::edge_ring>;  // TIM2
  using Outputs = MachineOutputs<Chip::gpiob_bsrr>;

  /// Kernel clock of the APB1 timers (TIM2..TIM4): twice PCLK1 when the APB1 prescaler is not 1 (RCC clock tree).
  [[nodiscard]] std::uint32_t apb1_timer_clock() const noexcept {
    return clocks_.pclk1_hz == clocks_.hclk_hz ? clocks_.pclk1_hz : 2 * clocks_.pclk1_hz;
  }

  static constexpr std::uint8_t step_pin_numbers[3] = {0, 1, 2};  // PA0, PA1, PA2
  static constexpr std::uint8_t dir_pin_numbers[3] = {3, 4, 5};   // PA3, PA4, PA5
  static constexpr std::uint32_t step_pins[3] = {0, 1, 2};
  static constexpr std::uint32_t dir_pins[3] = {3, 4, 5};

  static std::uint32_t pin_bits(const std::uint32_t (&pins)[3], std::uint32_t mask) noexcept {
    std::uint32_t bits = 0;
    for (std::size_t axis = 0; axis < 3; ++axis) {
      if ((mask & (1u << axis)) != 0) bits |= 1u << pins[axis];
    }
    return bits;
  }

  static inline Console console_{};
  static inline Edges edges_{};
  Clocks clocks_ = Chip::fallback_clocks;
};

}  // namespace curvestep::stm32
