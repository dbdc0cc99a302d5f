// SPDX-License-Identifier: MIT
// Shared Cortex-M start-up: reset, static initialisation, SysTick, fault reports.
#include <cstdint>

#include <curvestep/boards/stm32/mmio.hpp>
#include <curvestep/boards/stm32/startup.hpp>
#include <curvestep/boards/stm32/text.hpp>

extern "C" {
extern std::uint32_t _sidata, _sdata, _edata, _sbss, _ebss;
extern void (*__init_array_start[])();
extern void (*__init_array_end[])();
}

namespace curvestep::stm32 {
namespace {

volatile std::uint32_t tick_count = 0;
volatile std::uint32_t milliseconds = 0;
std::uint32_t millisecond_fraction = 0;  // milliseconds x tick_rate not yet counted
std::uint32_t tick_rate = 1000;
std::uint32_t tick_reload = 0;  // processor clocks per SysTick period (0: not started)
void (*tick_callback)(void*) = nullptr;
void* tick_context = nullptr;

void fault_put(char c) noexcept { curvestep_board_fault_putc(c); }

}  // namespace

std::uint32_t systick_count() noexcept { return tick_count; }
std::uint32_t systick_milliseconds() noexcept { return milliseconds; }

std::uint32_t systick_cycles() noexcept {
  for (;;) {
    const std::uint32_t ticks = tick_count;
    const std::uint32_t counter = reg(scs::systick_cvr);  // counts down from reload - 1
    if (ticks == tick_count) return ticks * tick_reload + (tick_reload - 1 - counter);
  }
}

bool start_systick(std::uint32_t hclk_hz, std::uint32_t rate_hz, void (*callback)(void*), void* context) noexcept {
  if (rate_hz == 0) return false;
  const std::uint32_t reload = hclk_hz / rate_hz;
  if (reload < 2 || reload > 0x1000000u) return false;
  tick_callback = callback;
  tick_context = context;
  tick_rate = rate_hz;
  tick_reload = reload;
  millisecond_fraction = 0;
  reg(scs::systick_csr) = 0;
  reg(scs::systick_rvr) = reload - 1;
  reg(scs::systick_cvr) = 0;
  // SysTick priority (SHPR3 bits 31:24): just below the UART so a byte is never lost to a long tick.
  *reinterpret_cast<volatile std::uint8_t*>(std::uintptr_t{0xE000ED23}) = 0x40;
  reg(scs::systick_csr) = 0b111;  // CLKSOURCE = processor clock, TICKINT, ENABLE
  return true;
}

[[noreturn]] void report_fault(const char* name, const std::uint32_t* frame) noexcept {
  disable_interrupts();
  put_text(fault_put, "\r\n");
  for (const char* p = name; *p != '\0'; ++p) fault_put(*p);
  put_text(fault_put, " pc=");
  put_hex(fault_put, frame[6]);
  put_text(fault_put, " lr=");
  put_hex(fault_put, frame[5]);
  put_text(fault_put, " xpsr=");
  put_hex(fault_put, frame[7]);
  put_text(fault_put, " cfsr=");
  put_hex(fault_put, reg(scs::cfsr));
  put_text(fault_put, " hfsr=");
  put_hex(fault_put, reg(scs::hfsr));
  put_text(fault_put, " mmfar=");
  put_hex(fault_put, reg(scs::mmfar));
  put_text(fault_put, " bfar=");
  put_hex(fault_put, reg(scs::bfar));
  put_text(fault_put, "\r\n");
  for (;;) {
  }
}

}  // namespace curvestep::stm32

extern "C" {

[[noreturn]] void Reset_Handler() {
  curvestep_board_early_init();
  for (std::uint32_t *source = &_sidata, *target = &_sdata; target < &_edata;) *target++ = *source++;
  for (std::uint32_t* target = &_sbss; target < &_ebss;) *target++ = 0;
  for (auto* constructor = __init_array_start; constructor < __init_array_end; ++constructor) (*constructor)();
  curvestep_main();
}

[[gnu::used]] void curvestep_fault_entry(const std::uint32_t* frame, std::uint32_t exception) {
  const char* name = "Fault";
  switch (exception) {
    case 3: name = "HardFault"; break;
    case 4: name = "MemManage"; break;
    case 5: name = "BusFault"; break;
    case 6: name = "UsageFault"; break;
    default: break;
  }
  if (exception < 3 || exception > 6) {
    // An enabled interrupt without a handler: report its number instead of hanging silently.
    curvestep::stm32::put_text(curvestep::stm32::fault_put, "\r\nUnexpected interrupt ipsr=");
    curvestep::stm32::put_decimal(curvestep::stm32::fault_put, exception);
  }
  curvestep::stm32::report_fault(name, frame);
}

// The fault frame is on MSP or PSP (EXC_RETURN bit 2); IPSR gives the exception number.
[[gnu::naked]] void HardFault_Handler() {
  asm volatile(
      "tst lr, #4\n\t"
      "ite eq\n\t"
      "mrseq r0, msp\n\t"
      "mrsne r0, psp\n\t"
      "mrs r1, ipsr\n\t"
      "b curvestep_fault_entry\n\t");
}
[[gnu::naked]] void MemManage_Handler() { asm volatile("b HardFault_Handler"); }
[[gnu::naked]] void BusFault_Handler() { asm volatile("b HardFault_Handler"); }
[[gnu::naked]] void UsageFault_Handler() { asm volatile("b HardFault_Handler"); }
[[gnu::naked]] void Default_Handler() { asm volatile("b HardFault_Handler"); }

void SysTick_Handler() {
  using namespace curvestep::stm32;
  tick_count = tick_count + 1;
  millisecond_fraction += 1000;  // one tick is 1000 / tick_rate ms
  while (millisecond_fraction >= tick_rate) {
    millisecond_fraction -= tick_rate;
    milliseconds = milliseconds + 1;
  }
  if (tick_callback != nullptr) tick_callback(tick_context);
}

}  // extern "C"
