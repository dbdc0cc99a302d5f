// SPDX-License-Identifier: MIT
// STM32F405 clock tree, GPIO and USART1 set-up from RM0090 (§6 RCC, §5 PWR, §8 GPIO, §30 USART, §3.5 flash).
#include "board.hpp"

#include <curvestep/boards/stm32/mmio.hpp>

namespace curvestep::boards {
namespace {

using stm32::reg;

constexpr std::uintptr_t rcc = 0x40023800;
constexpr std::uintptr_t rcc_cr = rcc + 0x00, rcc_pllcfgr = rcc + 0x04, rcc_cfgr = rcc + 0x08;
constexpr std::uintptr_t rcc_ahb1enr = rcc + 0x30, rcc_apb1enr = rcc + 0x40, rcc_apb2enr = rcc + 0x44;
constexpr std::uintptr_t pwr_cr = 0x40007000;
constexpr std::uintptr_t flash_acr = 0x40023C00;
constexpr std::uintptr_t gpioa = 0x40020000, gpiob = 0x40020400;
static_assert(Stm32F4Chip::gpioa_bsrr == gpioa + 0x18);
static_assert(Stm32F4Chip::gpiob_bsrr == gpiob + 0x18);
constexpr std::uintptr_t gpio_moder = 0x00, gpio_ospeedr = 0x08, gpio_afrl = 0x20, gpio_afrh = 0x24;

constexpr std::uint32_t cr_hseon = 1u << 16, cr_hserdy = 1u << 17, cr_pllon = 1u << 24, cr_pllrdy = 1u << 25;
constexpr std::uint32_t wait_attempts = 200'000;  // > 10 ms at 16 MHz; HSE needs ~2 ms

}  // namespace

/// HSE 25 MHz / M 25 * N 336 / P 2 = 168 MHz (Q 7: 48 MHz); AHB /1, APB1 /4 (42 MHz), APB2 /2 (84 MHz);
/// voltage scale 1, flash 5 wait states with prefetch and caches.
Clocks Stm32F4Chip::setup_clocks() noexcept {
  // RCC_CR resets to HSION | HSIRDY on silicon; all zero means an emulator without RCC, whose core
  // clock is fixed (QEMU's netduinoplus2 clocks its STM32F405 at 168 MHz): SysTick and the millisecond clock must use that.
  if (reg(rcc_cr) == 0) return {168'000'000, 42'000'000, 84'000'000, false, true};
  reg(rcc_apb1enr) = reg(rcc_apb1enr) | (1u << 28);  // PWREN
  reg(pwr_cr) = reg(pwr_cr) | (1u << 14);             // VOS: scale 1 (168 MHz)
  reg(rcc_cr) = reg(rcc_cr) | cr_hseon;
  if (!stm32::wait_for_bits(rcc_cr, cr_hserdy, cr_hserdy, wait_attempts)) {
    reg(rcc_cr) = reg(rcc_cr) & ~cr_hseon;
    return fallback_clocks;
  }
  // PLLQ 7 (27:24), PLLSRC HSE (22), PLLP /2 = 00 (17:16), PLLN 336 (14:6), PLLM 25 (5:0).
  reg(rcc_pllcfgr) = (7u << 24) | (1u << 22) | (336u << 6) | 25u;
  // PPRE2 /2 (100 at 15:13), PPRE1 /4 (101 at 12:10), HPRE /1.
  reg(rcc_cfgr) = (0b100u << 13) | (0b101u << 10);
  reg(rcc_cr) = reg(rcc_cr) | cr_pllon;
  if (!stm32::wait_for_bits(rcc_cr, cr_pllrdy, cr_pllrdy, wait_attempts)) {
    reg(rcc_cr) = reg(rcc_cr) & ~cr_pllon;
    return fallback_clocks;
  }
  reg(flash_acr) = (1u << 10) | (1u << 9) | (1u << 8) | 5u;  // DCEN, ICEN, PRFTEN, LATENCY 5 WS
  reg(rcc_cfgr) = (reg(rcc_cfgr) & ~0b11u) | 0b10u;         // SW = PLL
  if (!stm32::wait_for_bits(rcc_cfgr, 0b1100u, 0b1000u, wait_attempts)) {
    reg(rcc_cfgr) = reg(rcc_cfgr) & ~0b11u;
    return fallback_clocks;
  }
  return {168'000'000, 42'000'000, 84'000'000, true};
}

void Stm32F4Chip::setup_gpio() noexcept {
  reg(rcc_ahb1enr) = reg(rcc_ahb1enr) | (1u << 1) | (1u << 0);  // GPIOBEN, GPIOAEN
  reg(rcc_apb1enr) = reg(rcc_apb1enr) | (1u << 2) | (1u << 1);  // TIM4EN, TIM3EN
  reg(rcc_apb2enr) = reg(rcc_apb2enr) | (1u << 4);              // USART1EN
  stm32::barrier();
  // PA0..PA5 general-purpose outputs (01), PA6 and PA9/PA10 alternate function (10): AF2 = TIM3_CH1,
  // AF7 = USART1.
  std::uint32_t moder = reg(gpioa + gpio_moder);
  for (std::uint32_t pin = 0; pin < 6; ++pin) moder = (moder & ~(0b11u << (2 * pin))) | (0b01u << (2 * pin));
  moder = (moder & ~((0b11u << 12) | (0b11u << 18) | (0b11u << 20))) | (0b10u << 12) | (0b10u << 18) | (0b10u << 20);
  reg(gpioa + gpio_moder) = moder;
  reg(gpioa + gpio_ospeedr) = reg(gpioa + gpio_ospeedr) | 0xAAAu | (0b10u << 18);  // PA0-5, PA9 fast
  reg(gpioa + gpio_afrl) = (reg(gpioa + gpio_afrl) & ~(0xFu << 24)) | (2u << 24);
  reg(gpioa + gpio_afrh) = (reg(gpioa + gpio_afrh) & ~0xFF0u) | (7u << 4) | (7u << 8);
  // GPIOB: PB6 alternate function AF2 = TIM4_CH1, PB8..PB15 general-purpose outputs (01).
  reg(gpiob + gpio_moder) = (reg(gpiob + gpio_moder) & ~((0b11u << 12) | 0xFFFF0000u)) | (0b10u << 12) | 0x55550000u;
  reg(gpiob + gpio_afrl) = (reg(gpiob + gpio_afrl) & ~(0xFu << 24)) | (2u << 24);
}

void Stm32F4Chip::enable_step_timer() noexcept { reg(rcc_apb1enr) = reg(rcc_apb1enr) | 1u; }  // TIM2EN

}  // namespace curvestep::boards

extern "C" {
// CP10/CP11 full access before any floating-point instruction (PM0214 §4.6.1); lazy stacking stays on.
void curvestep_board_early_init() {
  curvestep::stm32::reg(curvestep::stm32::scs::cpacr) = curvestep::stm32::reg(curvestep::stm32::scs::cpacr) |
                                                       (0xFu << 20);
  curvestep::stm32::barrier();
}
void curvestep_board_fault_putc(char c) { curvestep::boards::Stm32F4Board::fault_putc(c); }
void USART1_IRQHandler() { curvestep::boards::Stm32F4Board::on_usart_interrupt(); }
void TIM2_IRQHandler() { curvestep::boards::Stm32F4Board::on_step_timer_interrupt(); }
}
