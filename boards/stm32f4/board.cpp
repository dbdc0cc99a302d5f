// SPDX-License-Identifier: MIT
// STM32F405 clock tree, GPIO and USART1 set-up from RM0090 (§6 RCC, §5 PWR, §8 GPIO, §30 USART, §3.5 flash).
#include "board.hpp"

#include <curvestep/boards/stm32/mmio.hpp>
#include <curvestep/boards/stm32/startup.hpp>
#include <curvestep/boards/stm32/step_edges.hpp>
#include <curvestep/boards/stm32/usart.hpp>

namespace curvestep::boards {
namespace {

using stm32::reg;

constexpr std::uintptr_t rcc = 0x40023800;
constexpr std::uintptr_t rcc_cr = rcc + 0x00, rcc_pllcfgr = rcc + 0x04, rcc_cfgr = rcc + 0x08;
constexpr std::uintptr_t rcc_ahb1enr = rcc + 0x30, rcc_apb1enr = rcc + 0x40, rcc_apb2enr = rcc + 0x44;
constexpr std::uintptr_t pwr_cr = 0x40007000;
constexpr std::uintptr_t flash_acr = 0x40023C00;
constexpr std::uintptr_t gpioa = 0x40020000;
constexpr std::uintptr_t gpio_moder = 0x00, gpio_ospeedr = 0x08, gpio_bsrr = 0x18, gpio_afrh = 0x24;
constexpr std::uintptr_t usart1 = 0x40011000;
constexpr unsigned usart1_irq = 37;

constexpr std::uint32_t cr_hseon = 1u << 16, cr_hserdy = 1u << 17, cr_pllon = 1u << 24, cr_pllrdy = 1u << 25;
constexpr std::uint32_t wait_attempts = 200'000;  // > 10 ms at 16 MHz; HSE needs ~2 ms
constexpr Clocks hsi_clocks{16'000'000, 16'000'000, 16'000'000, false};

using Console = stm32::Usart<usart1, usart1_irq, Stm32F4Board::console_buffer, Stm32F4Board::console_buffer>;
Console console;

using Edges = stm32::StepEdges<0x40000000, gpioa + gpio_bsrr, Stm32F4Board::edge_ring>;  // TIM2
Edges edges;
constexpr std::uint8_t step_pin_numbers[3] = {0, 1, 2};
constexpr std::uint8_t dir_pin_numbers[3] = {3, 4, 5};

constexpr std::uint32_t step_pins[3] = {0, 1, 2};  // PA0, PA1, PA2
constexpr std::uint32_t dir_pins[3] = {3, 4, 5};   // PA3, PA4, PA5

/// HSE 25 MHz / M 25 * N 336 / P 2 = 168 MHz (Q 7: 48 MHz); AHB /1, APB1 /4 (42 MHz), APB2 /2 (84 MHz);
/// voltage scale 1, flash 5 wait states with prefetch and caches.
Clocks setup_clocks() noexcept {
  // RCC_CR resets to HSION | HSIRDY on silicon; all zero means an emulator without RCC, whose core
  // clock is fixed (QEMU's netduinoplus2 clocks its STM32F405 at 168 MHz): SysTick and the millisecond clock must use that.
  if (reg(rcc_cr) == 0) return {168'000'000, 42'000'000, 84'000'000, false, true};
  reg(rcc_apb1enr) = reg(rcc_apb1enr) | (1u << 28);  // PWREN
  reg(pwr_cr) = reg(pwr_cr) | (1u << 14);             // VOS: scale 1 (168 MHz)
  reg(rcc_cr) = reg(rcc_cr) | cr_hseon;
  if (!stm32::wait_for_bits(rcc_cr, cr_hserdy, cr_hserdy, wait_attempts)) {
    reg(rcc_cr) = reg(rcc_cr) & ~cr_hseon;
    return hsi_clocks;
  }
  // PLLQ 7 (27:24), PLLSRC HSE (22), PLLP /2 = 00 (17:16), PLLN 336 (14:6), PLLM 25 (5:0).
  reg(rcc_pllcfgr) = (7u << 24) | (1u << 22) | (336u << 6) | 25u;
  // PPRE2 /2 (100 at 15:13), PPRE1 /4 (101 at 12:10), HPRE /1.
  reg(rcc_cfgr) = (0b100u << 13) | (0b101u << 10);
  reg(rcc_cr) = reg(rcc_cr) | cr_pllon;
  if (!stm32::wait_for_bits(rcc_cr, cr_pllrdy, cr_pllrdy, wait_attempts)) {
    reg(rcc_cr) = reg(rcc_cr) & ~cr_pllon;
    return hsi_clocks;
  }
  reg(flash_acr) = (1u << 10) | (1u << 9) | (1u << 8) | 5u;  // DCEN, ICEN, PRFTEN, LATENCY 5 WS
  reg(rcc_cfgr) = (reg(rcc_cfgr) & ~0b11u) | 0b10u;         // SW = PLL
  if (!stm32::wait_for_bits(rcc_cfgr, 0b1100u, 0b1000u, wait_attempts)) {
    reg(rcc_cfgr) = reg(rcc_cfgr) & ~0b11u;
    return hsi_clocks;
  }
  return {168'000'000, 42'000'000, 84'000'000, true};
}

void setup_gpio() noexcept {
  reg(rcc_ahb1enr) = reg(rcc_ahb1enr) | (1u << 0);  // GPIOAEN
  reg(rcc_apb2enr) = reg(rcc_apb2enr) | (1u << 4);  // USART1EN
  stm32::barrier();
  // PA0..PA5 general-purpose outputs (01), PA9/PA10 alternate function (10), AF7 = USART1.
  std::uint32_t moder = reg(gpioa + gpio_moder);
  for (std::uint32_t pin = 0; pin < 6; ++pin) moder = (moder & ~(0b11u << (2 * pin))) | (0b01u << (2 * pin));
  moder = (moder & ~((0b11u << 18) | (0b11u << 20))) | (0b10u << 18) | (0b10u << 20);
  reg(gpioa + gpio_moder) = moder;
  reg(gpioa + gpio_ospeedr) = reg(gpioa + gpio_ospeedr) | 0xAAAu | (0b10u << 18);  // PA0-5, PA9 fast
  reg(gpioa + gpio_afrh) = (reg(gpioa + gpio_afrh) & ~0xFF0u) | (7u << 4) | (7u << 8);
}

std::uint32_t pin_bits(const std::uint32_t (&pins)[3], std::uint32_t mask) noexcept {
  std::uint32_t bits = 0;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    if ((mask & (1u << axis)) != 0) bits |= 1u << pins[axis];
  }
  return bits;
}

}  // namespace

Clocks Stm32F4Board::init() noexcept {
  clocks_ = setup_clocks();
  setup_gpio();
  console.start(clocks_.pclk2_hz, baud, 0x20);
  stm32::enable_interrupts();
  return clocks_;
}

std::size_t Stm32F4Board::write(std::span<const std::uint8_t> bytes) noexcept { return console.write(bytes); }
void Stm32F4Board::write_all(std::span<const std::uint8_t> bytes) noexcept { console.write_all(bytes); }
bool Stm32F4Board::read(std::uint8_t& byte) noexcept { return console.read(byte); }
std::size_t Stm32F4Board::writable() const noexcept { return console.writable(); }
std::uint32_t Stm32F4Board::receive_overruns() const noexcept { return console.receive_overruns(); }

bool Stm32F4Board::start_tick(std::uint32_t rate_hz, void (*callback)(void*), void* context) noexcept {
  return stm32::start_systick(clocks_.hclk_hz, rate_hz, callback, context);
}
std::uint32_t Stm32F4Board::ticks() const noexcept { return stm32::systick_count(); }

void Stm32F4Board::set_directions(std::uint32_t positive_mask) noexcept {
  const std::uint32_t set = pin_bits(dir_pins, positive_mask);
  const std::uint32_t clear = pin_bits(dir_pins, ~positive_mask & 0b111u);
  reg(gpioa + gpio_bsrr) = set | (clear << 16);
}
void Stm32F4Board::raise_steps(std::uint32_t mask) noexcept { reg(gpioa + gpio_bsrr) = pin_bits(step_pins, mask); }
void Stm32F4Board::lower_steps(std::uint32_t mask) noexcept {
  reg(gpioa + gpio_bsrr) = pin_bits(step_pins, mask) << 16;
}

void Stm32F4Board::start_steps(std::uint32_t control_rate_hz) noexcept {
  reg(rcc_apb1enr) = reg(rcc_apb1enr) | 1u;  // TIM2EN
  stm32::barrier();
  // APB1 timers run at twice PCLK1 when the APB1 prescaler is not 1 (RCC clock tree).
  const std::uint32_t timer_clock = clocks_.pclk1_hz == clocks_.hclk_hz ? clocks_.pclk1_hz : 2 * clocks_.pclk1_hz;
  const std::uint32_t timer_hz = step_timing().timer_hz;
  edges.start(timer_clock, timer_hz, control_rate_hz == 0 ? timer_hz / 1000 : timer_hz / control_rate_hz,
              step_pin_numbers, dir_pin_numbers);
}
std::uint32_t Stm32F4Board::now_ms() const noexcept { return stm32::systick_milliseconds(); }
std::size_t Stm32F4Board::read(std::span<std::byte> into) noexcept {
  std::size_t count = 0;
  std::uint8_t byte = 0;
  while (count < into.size() && console.read(byte)) into[count++] = static_cast<std::byte>(byte);
  return count;
}
std::size_t Stm32F4Board::write(std::span<const std::byte> bytes) noexcept {
  return console.write(std::span(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()));
}
void Stm32F4Board::set_direction(std::uint64_t time_ticks, std::uint8_t axis, bool positive) noexcept {
  edges.push(time_ticks, axis, true, positive);
}
void Stm32F4Board::set_step(std::uint64_t time_ticks, std::uint8_t axis, bool high) noexcept {
  edges.push(time_ticks, axis, false, high);
}
void Stm32F4Board::fault_stop() noexcept { edges.stop(); }
std::uint32_t Stm32F4Board::edges_dropped() const noexcept { return edges.edges_dropped(); }

}  // namespace curvestep::boards

extern "C" {
// CP10/CP11 full access before any floating-point instruction (PM0214 §4.6.1); lazy stacking stays on.
void curvestep_board_early_init() {
  curvestep::stm32::reg(curvestep::stm32::scs::cpacr) = curvestep::stm32::reg(curvestep::stm32::scs::cpacr) |
                                                       (0xFu << 20);
  curvestep::stm32::barrier();
}
void curvestep_board_fault_putc(char c) { curvestep::boards::Console::write_polled(static_cast<std::uint8_t>(c)); }
void USART1_IRQHandler() { curvestep::boards::console.on_interrupt(); }
void TIM2_IRQHandler() { curvestep::boards::edges.on_interrupt(); }
}
