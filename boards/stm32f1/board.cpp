// SPDX-License-Identifier: MIT
// STM32F103 clock tree, GPIO and USART1 set-up from RM0008 (§7 RCC, §9 GPIO, §27 USART, §3.3.3 flash).
#include "board.hpp"

#include <curvestep/boards/stm32/mmio.hpp>

namespace curvestep::boards {
namespace {

using stm32::reg;

constexpr std::uintptr_t rcc = 0x40021000;
constexpr std::uintptr_t rcc_cr = rcc + 0x00, rcc_cfgr = rcc + 0x04, rcc_apb2enr = rcc + 0x18;
constexpr std::uintptr_t flash_acr = 0x40022000;
constexpr std::uintptr_t rcc_apb1enr = rcc + 0x1C;
constexpr std::uintptr_t gpioa = 0x40010800, gpiob = 0x40010C00;
static_assert(Stm32F1Chip::gpioa_bsrr == gpioa + 0x10);
static_assert(Stm32F1Chip::gpiob_bsrr == gpiob + 0x10);
constexpr std::uintptr_t gpio_crl = 0x00, gpio_crh = 0x04;

constexpr std::uint32_t cr_hseon = 1u << 16, cr_hserdy = 1u << 17, cr_pllon = 1u << 24, cr_pllrdy = 1u << 25;
constexpr std::uint32_t wait_attempts = 100'000;  // > 10 ms at 8 MHz; HSE needs ~2 ms

}  // namespace

/// HSE 8 MHz -> PLL x9 = 72 MHz; AHB /1, APB1 /2 (36 MHz max), APB2 /1; flash 2 wait states.
Clocks Stm32F1Chip::setup_clocks() noexcept {
  // RCC_CR resets to HSION | HSIRDY on silicon; all zero means an emulator without RCC, whose core
  // clock is fixed (QEMU's stm32vldiscovery clocks its STM32F100 at 24 MHz): SysTick and the millisecond clock must use that.
  if (reg(rcc_cr) == 0) return {24'000'000, 24'000'000, 24'000'000, false, true};
  reg(rcc_cr) = reg(rcc_cr) | cr_hseon;
  if (!stm32::wait_for_bits(rcc_cr, cr_hserdy, cr_hserdy, wait_attempts)) {
    reg(rcc_cr) = reg(rcc_cr) & ~cr_hseon;
    return fallback_clocks;
  }
  reg(flash_acr) = (1u << 4) | 2u;  // PRFTBE, LATENCY = 2 (48 < SYSCLK <= 72 MHz)
  // PLLMUL x9 (0111 at 21:18), PLLSRC = HSE (bit 16), ADCPRE /6 (10 at 15:14), PPRE1 /2 (100 at 10:8).
  reg(rcc_cfgr) = (0b0111u << 18) | (1u << 16) | (0b10u << 14) | (0b100u << 8);
  reg(rcc_cr) = reg(rcc_cr) | cr_pllon;
  if (!stm32::wait_for_bits(rcc_cr, cr_pllrdy, cr_pllrdy, wait_attempts)) {
    reg(rcc_cr) = reg(rcc_cr) & ~cr_pllon;
    return fallback_clocks;
  }
  reg(rcc_cfgr) = (reg(rcc_cfgr) & ~0b11u) | 0b10u;  // SW = PLL
  if (!stm32::wait_for_bits(rcc_cfgr, 0b1100u, 0b1000u, wait_attempts)) {
    reg(rcc_cfgr) = reg(rcc_cfgr) & ~0b11u;  // back to HSI
    return fallback_clocks;
  }
  return {72'000'000, 36'000'000, 72'000'000, true};
}

void Stm32F1Chip::setup_gpio() noexcept {
  reg(rcc_apb2enr) = reg(rcc_apb2enr) | (1u << 14) | (1u << 3) | (1u << 2) | (1u << 0);  // USART1EN, IOPBEN, IOPAEN, AFIOEN
  reg(rcc_apb1enr) = reg(rcc_apb1enr) | (1u << 2) | (1u << 1);                            // TIM4EN, TIM3EN
  // CRL: PA0..PA5 general-purpose push-pull output, 10 MHz (MODE = 01, CNF = 00); PA6 = TIM3_CH1
  // alternate-function push-pull, 2 MHz (MODE = 10, CNF = 10: 0xA).
  std::uint32_t crl = reg(gpioa + gpio_crl);
  for (std::uint32_t pin = 0; pin < 6; ++pin) crl = (crl & ~(0xFu << (4 * pin))) | (0x1u << (4 * pin));
  crl = (crl & ~(0xFu << 24)) | (0xAu << 24);
  reg(gpioa + gpio_crl) = crl;
  // GPIOB: PB6 = TIM4_CH1 alternate-function push-pull (0xA); PB8..PB15 push-pull outputs, 2 MHz (0x2).
  reg(gpiob + gpio_crl) = (reg(gpiob + gpio_crl) & ~(0xFu << 24)) | (0xAu << 24);
  reg(gpiob + gpio_crh) = 0x22222222u;
  // CRH: PA9 alternate-function push-pull 50 MHz (0xB), PA10 floating input (0x4).
  std::uint32_t crh = reg(gpioa + gpio_crh);
  crh = (crh & ~(0xFFu << 4)) | (0xBu << 4) | (0x4u << 8);
  reg(gpioa + gpio_crh) = crh;
}

void Stm32F1Chip::enable_step_timer() noexcept { reg(rcc + 0x1C) = reg(rcc + 0x1C) | 1u; }  // TIM2EN

}  // namespace curvestep::boards

extern "C" {
void curvestep_board_early_init() {}
void curvestep_board_fault_putc(char c) { curvestep::boards::Stm32F1Board::fault_putc(c); }
void USART1_IRQHandler() { curvestep::boards::Stm32F1Board::on_usart_interrupt(); }
void TIM2_IRQHandler() { curvestep::boards::Stm32F1Board::on_step_timer_interrupt(); }
}
