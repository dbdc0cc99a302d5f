// SPDX-License-Identifier: MIT
// STM32F103 clock tree, GPIO and USART1 set-up from RM0008 (§7 RCC, §9 GPIO, §27 USART, §3.3.3 flash).
#include "board.hpp"

#include <curvestep/boards/stm32/mmio.hpp>
#include <curvestep/boards/stm32/startup.hpp>
#include <curvestep/boards/stm32/step_edges.hpp>
#include <curvestep/boards/stm32/usart.hpp>

namespace curvestep::boards {
namespace {

using stm32::reg;

constexpr std::uintptr_t rcc = 0x40021000;
constexpr std::uintptr_t rcc_cr = rcc + 0x00, rcc_cfgr = rcc + 0x04, rcc_apb2enr = rcc + 0x18;
constexpr std::uintptr_t flash_acr = 0x40022000;
constexpr std::uintptr_t gpioa = 0x40010800;
constexpr std::uintptr_t gpio_crl = 0x00, gpio_crh = 0x04, gpio_bsrr = 0x10;
constexpr std::uintptr_t usart1 = 0x40013800;
constexpr unsigned usart1_irq = 37;

constexpr std::uint32_t cr_hseon = 1u << 16, cr_hserdy = 1u << 17, cr_pllon = 1u << 24, cr_pllrdy = 1u << 25;
constexpr std::uint32_t wait_attempts = 100'000;  // > 10 ms at 8 MHz; HSE needs ~2 ms

using Console = stm32::Usart<usart1, usart1_irq, Stm32F1Board::console_buffer, Stm32F1Board::console_buffer>;
Console console;

using Edges = stm32::StepEdges<0x40000000, gpioa + gpio_bsrr, Stm32F1Board::edge_ring>;  // TIM2
Edges edges;
constexpr std::uint8_t step_pin_numbers[3] = {0, 1, 2};
constexpr std::uint8_t dir_pin_numbers[3] = {3, 4, 5};

constexpr std::uint32_t step_pins[3] = {0, 1, 2};  // PA0, PA1, PA2
constexpr std::uint32_t dir_pins[3] = {3, 4, 5};   // PA3, PA4, PA5

/// HSE 8 MHz -> PLL x9 = 72 MHz; AHB /1, APB1 /2 (36 MHz max), APB2 /1; flash 2 wait states.
Clocks setup_clocks() noexcept {
  // RCC_CR resets to HSION | HSIRDY on silicon; all zero means an emulator without RCC, whose core
  // clock is fixed (QEMU's stm32vldiscovery clocks its STM32F100 at 24 MHz): SysTick and the millisecond clock must use that.
  if (reg(rcc_cr) == 0) return {24'000'000, 24'000'000, 24'000'000, false, true};
  reg(rcc_cr) = reg(rcc_cr) | cr_hseon;
  if (!stm32::wait_for_bits(rcc_cr, cr_hserdy, cr_hserdy, wait_attempts)) {
    reg(rcc_cr) = reg(rcc_cr) & ~cr_hseon;
    return {8'000'000, 8'000'000, 8'000'000, false};
  }
  reg(flash_acr) = (1u << 4) | 2u;  // PRFTBE, LATENCY = 2 (48 < SYSCLK <= 72 MHz)
  // PLLMUL x9 (0111 at 21:18), PLLSRC = HSE (bit 16), ADCPRE /6 (10 at 15:14), PPRE1 /2 (100 at 10:8).
  reg(rcc_cfgr) = (0b0111u << 18) | (1u << 16) | (0b10u << 14) | (0b100u << 8);
  reg(rcc_cr) = reg(rcc_cr) | cr_pllon;
  if (!stm32::wait_for_bits(rcc_cr, cr_pllrdy, cr_pllrdy, wait_attempts)) {
    reg(rcc_cr) = reg(rcc_cr) & ~cr_pllon;
    return {8'000'000, 8'000'000, 8'000'000, false};
  }
  reg(rcc_cfgr) = (reg(rcc_cfgr) & ~0b11u) | 0b10u;  // SW = PLL
  if (!stm32::wait_for_bits(rcc_cfgr, 0b1100u, 0b1000u, wait_attempts)) {
    reg(rcc_cfgr) = reg(rcc_cfgr) & ~0b11u;  // back to HSI
    return {8'000'000, 8'000'000, 8'000'000, false};
  }
  return {72'000'000, 36'000'000, 72'000'000, true};
}

void setup_gpio() noexcept {
  reg(rcc_apb2enr) = reg(rcc_apb2enr) | (1u << 14) | (1u << 2) | (1u << 0);  // USART1EN, IOPAEN, AFIOEN
  // CRL: PA0..PA5 general-purpose push-pull output, 10 MHz (MODE = 01, CNF = 00).
  std::uint32_t crl = reg(gpioa + gpio_crl);
  for (std::uint32_t pin = 0; pin < 6; ++pin) crl = (crl & ~(0xFu << (4 * pin))) | (0x1u << (4 * pin));
  reg(gpioa + gpio_crl) = crl;
  // CRH: PA9 alternate-function push-pull 50 MHz (0xB), PA10 floating input (0x4).
  std::uint32_t crh = reg(gpioa + gpio_crh);
  crh = (crh & ~(0xFFu << 4)) | (0xBu << 4) | (0x4u << 8);
  reg(gpioa + gpio_crh) = crh;
}

std::uint32_t pin_bits(const std::uint32_t (&pins)[3], std::uint32_t mask) noexcept {
  std::uint32_t bits = 0;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    if ((mask & (1u << axis)) != 0) bits |= 1u << pins[axis];
  }
  return bits;
}

}  // namespace

Clocks Stm32F1Board::init() noexcept {
  clocks_ = setup_clocks();
  setup_gpio();
  console.start(clocks_.pclk2_hz, baud, 0x20);
  stm32::enable_interrupts();
  return clocks_;
}

std::size_t Stm32F1Board::write(std::span<const std::uint8_t> bytes) noexcept { return console.write(bytes); }
void Stm32F1Board::write_all(std::span<const std::uint8_t> bytes) noexcept { console.write_all(bytes); }
bool Stm32F1Board::read(std::uint8_t& byte) noexcept { return console.read(byte); }
std::size_t Stm32F1Board::writable() const noexcept { return console.writable(); }
std::uint32_t Stm32F1Board::receive_overruns() const noexcept { return console.receive_overruns(); }

bool Stm32F1Board::start_tick(std::uint32_t rate_hz, void (*callback)(void*), void* context) noexcept {
  return stm32::start_systick(clocks_.hclk_hz, rate_hz, callback, context);
}
std::uint32_t Stm32F1Board::ticks() const noexcept { return stm32::systick_count(); }

void Stm32F1Board::set_directions(std::uint32_t positive_mask) noexcept {
  const std::uint32_t set = pin_bits(dir_pins, positive_mask);
  const std::uint32_t clear = pin_bits(dir_pins, ~positive_mask & 0b111u);
  reg(gpioa + gpio_bsrr) = set | (clear << 16);
}
void Stm32F1Board::raise_steps(std::uint32_t mask) noexcept { reg(gpioa + gpio_bsrr) = pin_bits(step_pins, mask); }
void Stm32F1Board::lower_steps(std::uint32_t mask) noexcept {
  reg(gpioa + gpio_bsrr) = pin_bits(step_pins, mask) << 16;
}

void Stm32F1Board::start_steps(std::uint32_t control_rate_hz) noexcept {
  reg(rcc + 0x1C) = reg(rcc + 0x1C) | 1u;  // TIM2EN
  stm32::barrier();
  // APB1 timers run at twice PCLK1 when the APB1 prescaler is not 1 (RCC clock tree).
  const std::uint32_t timer_clock = clocks_.pclk1_hz == clocks_.hclk_hz ? clocks_.pclk1_hz : 2 * clocks_.pclk1_hz;
  const std::uint32_t timer_hz = step_timing().timer_hz;
  edges.start(timer_clock, timer_hz, control_rate_hz == 0 ? timer_hz / 1000 : timer_hz / control_rate_hz,
              step_pin_numbers, dir_pin_numbers);
}
std::uint32_t Stm32F1Board::now_ms() const noexcept { return stm32::systick_milliseconds(); }
std::size_t Stm32F1Board::read(std::span<std::byte> into) noexcept {
  std::size_t count = 0;
  std::uint8_t byte = 0;
  while (count < into.size() && console.read(byte)) into[count++] = static_cast<std::byte>(byte);
  return count;
}
std::size_t Stm32F1Board::write(std::span<const std::byte> bytes) noexcept {
  return console.write(std::span(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()));
}
void Stm32F1Board::set_direction(std::uint64_t time_ticks, std::uint8_t axis, bool positive) noexcept {
  edges.push(time_ticks, axis, true, positive);
}
void Stm32F1Board::set_step(std::uint64_t time_ticks, std::uint8_t axis, bool high) noexcept {
  edges.push(time_ticks, axis, false, high);
}
void Stm32F1Board::fault_stop() noexcept { edges.stop(); }
std::uint32_t Stm32F1Board::edges_dropped() const noexcept { return edges.edges_dropped(); }

}  // namespace curvestep::boards

extern "C" {
void curvestep_board_early_init() {}
void curvestep_board_fault_putc(char c) { curvestep::boards::Console::write_polled(static_cast<std::uint8_t>(c)); }
void USART1_IRQHandler() { curvestep::boards::console.on_interrupt(); }
void TIM2_IRQHandler() { curvestep::boards::edges.on_interrupt(); }
}
