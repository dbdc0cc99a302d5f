// SPDX-License-Identifier: MIT
// A fault-injecting byte relay between a host and a controller, for link tests: drops, corrupts,
// duplicates and delays bytes at configurable rates from a seeded generator, and can cut the
// line after a number of bytes (the "link dies mid-job" case).
//
// Delays keep byte order, as a serial line does: a delayed byte holds back every byte behind
// it in the same direction. Each direction has its own generator (seeded from `seed`), so a run
// is reproducible for a given interleaving of reads.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>

#include <curvestep/host/link/transport.hpp>

namespace curvestep::host::link {

/// Fault rates (probability per byte, 0..1) and switches.
struct FaultSettings {
  double drop = 0;               ///< byte is lost
  double corrupt = 0;            ///< byte gets one random bit flipped
  double duplicate = 0;          ///< byte is sent twice
  double delay = 0;              ///< byte (and what follows it) waits delay_ms
  int delay_ms = 20;             ///< length of one delay
  std::uint64_t seed = 1;        ///< generator seed
  bool to_device = true;         ///< apply faults to host -> device bytes
  bool to_host = true;           ///< apply faults to device -> host bytes
  std::size_t cut_after_bytes = 0;  ///< after this many host -> device bytes, forward nothing more (0: never)
};

/// What the proxy did.
struct FaultCounters {
  std::size_t bytes_to_device = 0;  ///< bytes read from the host
  std::size_t bytes_to_host = 0;    ///< bytes read from the device
  std::size_t dropped = 0;          ///< bytes dropped
  std::size_t corrupted = 0;        ///< bytes corrupted
  std::size_t duplicated = 0;       ///< bytes duplicated
  std::size_t delayed = 0;          ///< delays started
  bool cut = false;                 ///< the line was cut
};

/// Relays between `host` and `device` until `stop` is set or a side closes (a closed side ends
/// the relay quietly). Counters are updated as it goes.
void run_fault_proxy(Transport& host, Transport& device, const FaultSettings& settings, const std::atomic<bool>& stop,
                     FaultCounters& counters);

}  // namespace curvestep::host::link
