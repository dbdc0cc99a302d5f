/* SPDX-License-Identifier: MIT
 * What QEMU's STM32F405 TIM2 model (hw/timer/stm32f2xx_timer.c) does with the edge player's
 * settings (step_edges.hpp: PSC 83 for 1 MHz from 84 MHz, ARR 0xFFFF, UG, CCR1 + CC1IE, CEN).
 * Not a CTest test: the evidence behind docs/boards.md, "Step edges in QEMU". Build and run:
 *   arm-none-eabi-gcc -mcpu=cortex-m4 -mthumb -O1 -nostdlib -ffreestanding -o probe.elf \
 *     -Wl,-e,reset_handler,--section-start=.vectors=0x08000000,-Ttext=0x08000400,-Tbss=0x20000000 \
 *     tests/qemu/step_edges_tim2_probe.c
 *   timeout 3 qemu-system-arm -M netduinoplus2 -display none -monitor none -serial stdio -kernel probe.elf \
 *     -icount shift=3
 * (add -DCC1_ONLY for DIER = CC1IE alone). It prints SR, CNT and the SysTick time (168 MHz core,
 * 1 kHz) at each TIM2 interrupt and every 100 ms. QEMU 7.2.22 (Debian), -icount shift=3:
 *   irq 0 sr=00000001 cnt=00012002 t_ms=6+193us
 *   irq 1 sr=00000001 cnt=00024003 t_ms=12+386us     (every 6.19 ms)
 *   t_ms=100 cnt=00122a57 sr=00000000 irqs=16
 *   -DCC1_ONLY: t_ms=1000 cnt=00b5a6fb sr=00000000 irqs=0
 * i.e. SR never shows CC1IF and CC1IE alone gives no interrupt at all (CCR1 is a plain register);
 * CNT is not reloaded at ARR (it reads 0x122a57 > 0xFFFF after 100 ms) and counts at
 * 11.9 MHz = 1 GHz / (PSC + 1) whatever RCC says; UIF comes every t0 + 65535 x 84 ns, t0 being the
 * virtual time of the last PSC/EGR write (the model arms its alarm at now + the absolute time of
 * the wrap): 6.19 ms here, where t0 is 0.7 ms; 0.1 to 1 s in the firmware, which starts TIM2 again
 * when the machine configuration arrives.
 */
#include <stdint.h>

#define REG(address) (*(volatile uint32_t *)(address))
#define TIM2 0x40000000u
#define USART1 0x40011000u
#define SYST_CSR 0xE000E010u
#define SYST_RVR 0xE000E014u
#define SYST_CVR 0xE000E018u

static volatile uint32_t milliseconds;
static volatile uint32_t interrupts;

static void put(char c) { REG(USART1 + 0x04) = (uint8_t)c; } /* QEMU's USART sends at once */
static void text(const char *s) {
  while (*s) put(*s++);
}
static void hex(uint32_t v) {
  for (int shift = 28; shift >= 0; shift -= 4) put("0123456789abcdef"[(v >> shift) & 15]);
}
static void decimal(uint32_t v) {
  char digits[11];
  int i = 10;
  digits[i] = 0;
  do digits[--i] = (char)('0' + v % 10), v /= 10;
  while (v);
  text(digits + i);
}

static void systick_handler(void) { milliseconds = milliseconds + 1; }

static void tim2_handler(void) {
  const uint32_t sr = REG(TIM2 + 0x10), cnt = REG(TIM2 + 0x24), cvr = REG(SYST_CVR), now = milliseconds;
  REG(TIM2 + 0x10) = ~sr & 0x1FFFu; /* rc_w0: clear what was seen */
  if (interrupts < 20) {
    text("irq "), decimal(interrupts), text(" sr="), hex(sr), text(" cnt="), hex(cnt);
    text(" t_ms="), decimal(now), text("+"), decimal((167999 - cvr) / 168), text("us\r\n");
  }
  interrupts = interrupts + 1;
  REG(TIM2 + 0x34) = (cnt + 1000) & 0xFFFFu; /* next compare 1000 counts on, as arm() would */
}

void reset_handler(void);
__attribute__((section(".vectors"), used)) const void *const vectors[16 + 29] = {
    (void *)0x20010000, (void *)reset_handler, [15] = (void *)systick_handler, [16 + 28] = (void *)tim2_handler};

void reset_handler(void) {
  REG(USART1 + 0x0C) = (1u << 13) | (1u << 3); /* UE, TE */
  text("tim2 probe\r\n");
  REG(SYST_RVR) = 167999, REG(SYST_CVR) = 0, REG(SYST_CSR) = 7; /* 1 kHz from the 168 MHz core */
  REG(TIM2 + 0x00) = 0;
  REG(TIM2 + 0x28) = 83;     /* PSC: 84 MHz timer clock -> 1 MHz */
  REG(TIM2 + 0x2C) = 0xFFFF; /* ARR */
  REG(TIM2 + 0x14) = 1;      /* UG */
  REG(TIM2 + 0x10) = 0;
  REG(TIM2 + 0x34) = 1000; /* CCR1 */
#ifdef CC1_ONLY
  REG(TIM2 + 0x0C) = 2; /* CC1IE */
#else
  REG(TIM2 + 0x0C) = 3; /* UIE | CC1IE */
#endif
  REG(TIM2 + 0x00) = 1;       /* CEN */
  REG(0xE000E100) = 1u << 28; /* NVIC: TIM2 */
  for (uint32_t last = 0;;) {
    if (milliseconds - last >= 100) {
      last = milliseconds;
      text("t_ms="), decimal(last), text(" cnt="), hex(REG(TIM2 + 0x24)), text(" sr="), hex(REG(TIM2 + 0x10));
      text(" irqs="), decimal(interrupts), text("\r\n");
    }
  }
}
