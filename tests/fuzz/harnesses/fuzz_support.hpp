// SPDX-License-Identifier: MIT
// Helpers shared by the libFuzzer harnesses: a byte reader over the fuzz input and a finding report.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <span>

#include <curvestep/core/contract.hpp>

namespace curvestep::fuzz {

/// A finding: print what broke and abort, so libFuzzer saves the input as a crash.
[[noreturn]] inline void finding(const char* what) {
  std::fprintf(stderr, "curvestep fuzz finding: %s\n", what);
  std::abort();
}

/// Contract violations are findings too (the default handler traps; this one names the check).
inline void report_contract(const char* condition, const char* file, int line) {
  std::fprintf(stderr, "curvestep fuzz finding: contract violated: %s at %s:%d\n", condition, file, line);
  std::abort();
}

/// Checks a property of the code under test; a violation is a finding.
#define CURVESTEP_FUZZ_ASSERT(condition) \
  ((condition) ? static_cast<void>(0) : ::curvestep::fuzz::finding(#condition " (" __FILE__ ")"))

/// Consumes the fuzz input front to back; past the end every read returns zero.
class InputReader {
 public:
  InputReader(const std::uint8_t* data, std::size_t size) noexcept : data_(data), size_(size) {}

  [[nodiscard]] bool empty() const noexcept { return read_ >= size_; }
  [[nodiscard]] std::size_t remaining() const noexcept { return size_ - read_; }

  [[nodiscard]] std::uint8_t u8() noexcept { return read_ < size_ ? data_[read_++] : 0; }
  [[nodiscard]] std::uint16_t u16() noexcept {
    const auto low = u8();
    return static_cast<std::uint16_t>(low | (u8() << 8));
  }
  [[nodiscard]] std::uint32_t u32() noexcept {
    const std::uint32_t low = u16();
    return low | (static_cast<std::uint32_t>(u16()) << 16);
  }
  [[nodiscard]] std::uint64_t u64() noexcept {
    const std::uint64_t low = u32();
    return low | (static_cast<std::uint64_t>(u32()) << 32);
  }
  /// A value in [lo, hi] from 16 bits.
  [[nodiscard]] double in_range(double lo, double hi) noexcept { return lo + (hi - lo) * u16() / 65535.0; }
  /// Any bit pattern as a double (NaN, infinity, denormals included).
  [[nodiscard]] double any_double() noexcept {
    const std::uint64_t bits = u64();
    double value = 0;
    std::memcpy(&value, &bits, sizeof value);
    return value;
  }
  /// The next n bytes (fewer at the end of the input).
  [[nodiscard]] std::span<const std::uint8_t> bytes(std::size_t n) noexcept {
    const std::size_t take = n < remaining() ? n : remaining();
    const std::span<const std::uint8_t> out(data_ + read_, take);
    read_ += take;
    return out;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t read_ = 0;
};

}  // namespace curvestep::fuzz
