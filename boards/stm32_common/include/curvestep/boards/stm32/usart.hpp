// SPDX-License-Identifier: MIT
// Interrupt-driven USART with receive and transmit ring buffers (STM32F1/F2/F4 register layout).
//
// Registers (RM0008 §27.6 for F1, RM0090 §30.6 for F4; the same layout on both):
// SR 0x00 (TXE bit 7, TC 6, RXNE 5, ORE 3), DR 0x04, BRR 0x08, CR1 0x0C (UE 13, TXEIE 7,
// RXNEIE 5, TE 3, RE 2). With 16x oversampling BRR = f_pclk / baud (mantissa.fraction in 1/16).
//
// Transmission. write() queues bytes and enables TXEIE; on silicon the TXE interrupt moves one
// byte per interrupt into DR. The handler loops "while TXE and bytes queued", so it also drains
// the queue on an emulator whose USART is synchronous and never raises the TXE interrupt (QEMU
// 7.2's stm32f2xx_usart model): write() marks the interrupt pending once after queueing, which
// on silicon merely runs the handler one extra time.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include <curvestep/boards/stm32/mmio.hpp>
#include <curvestep/boards/stm32/ring_buffer.hpp>

namespace curvestep::stm32 {

/// One USART at `Base` with NVIC line `Irq`, buffering RxCapacity/TxCapacity bytes (powers of two).
template <std::uintptr_t Base, unsigned Irq, std::size_t RxCapacity, std::size_t TxCapacity>
class Usart {
 public:
  static constexpr std::uint32_t sr_txe = 1u << 7;      ///< transmit data register empty
  static constexpr std::uint32_t sr_rxne = 1u << 5;     ///< receive data register not empty
  static constexpr std::uint32_t sr_ore = 1u << 3;      ///< receive overrun
  static constexpr std::uint32_t cr1_ue = 1u << 13;     ///< USART enable
  static constexpr std::uint32_t cr1_txeie = 1u << 7;   ///< TXE interrupt enable
  static constexpr std::uint32_t cr1_rxneie = 1u << 5;  ///< RXNE interrupt enable
  static constexpr std::uint32_t cr1_te = 1u << 3;      ///< transmitter enable
  static constexpr std::uint32_t cr1_re = 1u << 2;      ///< receiver enable

  /// Programs 8N1 at `baud` from the peripheral clock `pclk_hz` and enables the receive interrupt.
  /// The peripheral clock and the pins must already be enabled and configured.
  void start(std::uint32_t pclk_hz, std::uint32_t baud, std::uint8_t priority) noexcept {
    reg(Base + cr1) = 0;
    reg(Base + brr) = (pclk_hz + baud / 2) / baud;
    reg(Base + cr2) = 0;
    reg(Base + cr3) = 0;
    reg(Base + cr1) = cr1_ue | cr1_te | cr1_re | cr1_rxneie;
    nvic_enable(Irq, priority);
  }

  /// Queues as many bytes of `bytes` as fit; returns how many were queued.
  std::size_t write(std::span<const std::uint8_t> bytes) noexcept {
    std::size_t queued = 0;
    while (queued < bytes.size() && tx_.push(bytes[queued])) ++queued;
    if (queued > 0) kick();
    return queued;
  }

  /// Queues every byte of `bytes`, waiting for room (the interrupt drains the queue).
  void write_all(std::span<const std::uint8_t> bytes) noexcept {
    while (!bytes.empty()) {
      const std::size_t queued = write(bytes);
      bytes = bytes.subspan(queued);
      if (!bytes.empty()) wait_for_interrupt();
    }
  }

  /// Takes the oldest received byte into `byte`; false when none is waiting.
  bool read(std::uint8_t& byte) noexcept { return rx_.pop(byte); }

  /// Bytes waiting to be read.
  [[nodiscard]] std::size_t readable() const noexcept { return rx_.size(); }
  /// Room left in the transmit queue.
  [[nodiscard]] std::size_t writable() const noexcept { return tx_.free_space(); }
  /// True once every queued byte has been handed to the data register.
  [[nodiscard]] bool transmit_idle() const noexcept { return tx_.empty(); }
  /// Received bytes lost because the receive queue was full or the hardware overran.
  [[nodiscard]] std::uint32_t receive_overruns() const noexcept { return overruns_; }

  /// The interrupt handler body: moves received bytes in and queued bytes out.
  void on_interrupt() noexcept {
    std::uint32_t status = reg(Base + sr);
    while ((status & (sr_rxne | sr_ore)) != 0) {
      const auto byte = static_cast<std::uint8_t>(reg(Base + dr) & 0xFFu);  // reading DR clears RXNE/ORE
      if ((status & sr_ore) != 0) overruns_ = overruns_ + 1;
      if ((status & sr_rxne) != 0 && !rx_.push(byte)) overruns_ = overruns_ + 1;
      status = reg(Base + sr);
    }
    std::uint8_t byte = 0;
    while ((reg(Base + sr) & sr_txe) != 0) {
      if (!tx_.pop(byte)) {
        reg(Base + cr1) = reg(Base + cr1) & ~cr1_txeie;
        return;
      }
      reg(Base + dr) = byte;
    }
  }

  /// Sends one byte by polling, interrupts not needed (for fault reports). Waits for TXE.
  static void write_polled(std::uint8_t byte) noexcept {
    while ((reg(Base + sr) & sr_txe) == 0) {
    }
    reg(Base + dr) = byte;
  }

 private:
  static constexpr std::uintptr_t sr = 0x00, dr = 0x04, brr = 0x08, cr1 = 0x0C, cr2 = 0x10, cr3 = 0x14;

  void kick() noexcept {
    {
      const CriticalSection guard;
      reg(Base + cr1) = reg(Base + cr1) | cr1_txeie;
    }
    nvic_set_pending(Irq);
  }

  RingBuffer<RxCapacity> rx_;
  RingBuffer<TxCapacity> tx_;
  volatile std::uint32_t overruns_ = 0;
};

}  // namespace curvestep::stm32
