// SPDX-License-Identifier: MIT
// The benchmark marks: an out-of-line function whose entry address the instruction counter looks for.
#include <cstdint>

extern "C" [[gnu::noinline, gnu::used]] void curvestep_bench_mark(std::uint32_t id) {
  asm volatile("" ::"r"(id) : "memory");
}
