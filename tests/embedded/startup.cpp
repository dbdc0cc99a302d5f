// SPDX-License-Identifier: MIT
// Bare-metal entry for the allocation probe: vector table, .data/.bss set-up, then every probe.
#include <cstdint>

#include "probe.hpp"

extern "C" {
extern std::uint32_t _sidata, _sdata, _edata, _sbss, _ebss, _estack;
[[noreturn]] void Reset_Handler();
}

[[gnu::section(".isr_vector"), gnu::used]] const void* const vector_table[2] = {&_estack,
                                                                                 reinterpret_cast<const void*>(&Reset_Handler)};

extern "C" [[noreturn]] void Reset_Handler() {
  for (std::uint32_t *src = &_sidata, *dst = &_sdata; dst < &_edata;) *dst++ = *src++;
  for (std::uint32_t* dst = &_sbss; dst < &_ebss;) *dst++ = 0;
  curvestep::probe::run_all();
  for (;;) {
  }
}
