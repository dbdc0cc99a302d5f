// SPDX-License-Identifier: MIT
#include <curvestep/host/link/fault_proxy.hpp>

#include <array>
#include <chrono>
#include <deque>
#include <random>
#include <utility>

namespace curvestep::host::link {
namespace {

using Clock = std::chrono::steady_clock;

/// One direction: faults applied on the way in, bytes released in order when due.
class Lane {
 public:
  Lane(const FaultSettings& settings, bool faulty, std::uint64_t seed, FaultCounters& counters)
      : settings_(settings), faulty_(faulty), random_(seed), counters_(counters) {}

  void accept(std::byte b, Clock::time_point now) {
    if (faulty_) {
      if (chance(settings_.drop)) {
        ++counters_.dropped;
        return;
      }
      if (chance(settings_.corrupt)) {
        b ^= std::byte{static_cast<std::uint8_t>(1u << bit_(random_))};
        ++counters_.corrupted;
      }
      if (chance(settings_.delay)) {
        hold_until_ = std::max(hold_until_, now) + std::chrono::milliseconds(settings_.delay_ms);
        ++counters_.delayed;
      }
    }
    const auto release = std::max(hold_until_, now);
    queue_.emplace_back(release, b);
    if (faulty_ && chance(settings_.duplicate)) {
      queue_.emplace_back(release, b);
      ++counters_.duplicated;
    }
  }

  /// Writes every byte that is due.
  void flush(Transport& out, Clock::time_point now) {
    std::array<std::byte, 512> chunk{};
    std::size_t size = 0;
    while (!queue_.empty() && queue_.front().first <= now && size < chunk.size()) {
      chunk[size++] = queue_.front().second;
      queue_.pop_front();
    }
    if (size > 0) out.write(std::span<const std::byte>(chunk.data(), size));
  }

  [[nodiscard]] bool waiting() const noexcept { return !queue_.empty(); }

 private:
  bool chance(double p) { return p > 0 && uniform_(random_) < p; }

  const FaultSettings& settings_;
  bool faulty_;
  std::mt19937_64 random_;
  std::uniform_real_distribution<double> uniform_{0.0, 1.0};
  std::uniform_int_distribution<unsigned> bit_{0, 7};
  FaultCounters& counters_;
  std::deque<std::pair<Clock::time_point, std::byte>> queue_;
  Clock::time_point hold_until_{};
};

}  // namespace

void run_fault_proxy(Transport& host, Transport& device, const FaultSettings& settings, const std::atomic<bool>& stop,
                     FaultCounters& counters) {
  Lane to_device(settings, settings.to_device, settings.seed, counters);
  Lane to_host(settings, settings.to_host, settings.seed ^ 0x9E3779B97F4A7C15ull, counters);
  std::array<std::byte, 512> buffer{};
  try {
    while (!stop.load()) {
      const int wait = (to_device.waiting() || to_host.waiting()) ? 0 : 2;
      std::size_t n = host.read(buffer, wait);
      auto now = Clock::now();
      for (std::size_t i = 0; i < n; ++i) {
        ++counters.bytes_to_device;
        if (settings.cut_after_bytes != 0 && counters.bytes_to_device > settings.cut_after_bytes) {
          counters.cut = true;
          continue;
        }
        to_device.accept(buffer[i], now);
      }
      n = device.read(buffer, 1);
      now = Clock::now();
      for (std::size_t i = 0; i < n; ++i) {
        ++counters.bytes_to_host;
        if (counters.cut) continue;  // a cut line carries nothing either way
        to_host.accept(buffer[i], now);
      }
      to_device.flush(device, now);
      to_host.flush(host, now);
    }
  } catch (const TransportError&) {
    // One side went away: the relay ends.
  }
}

}  // namespace curvestep::host::link
