// SPDX-License-Identifier: MIT
// Weights and feeds rounded to Q16.16 for the wire.
#include <curvestep/host/wire_value.hpp>

#include <curvestep/core/fixed/fixed.hpp>
#include <curvestep/host/csv.hpp>

namespace curvestep::host {

WireValue round_for_wire(double value, WireQuantity quantity, std::string_view name) {
  const bool weight = quantity == WireQuantity::Weight;
  const std::string what = name.empty() ? std::string(weight ? "weight" : "feed") : std::string(name);
  const auto q = Q16_16::from_double(value);
  if (!q) return {0, what + " " + format_number(value) + " is outside the Q16.16 range (at most 32767.99998)", Error::FixedOverflow};
  if (value > 0 && q.value().raw() == 0) {
    return {0, what + " " + format_number(value) + " rounds to 0 in Q16.16 (the smallest positive value is 2^-16 = 1.52588e-05)",
            weight ? Error::NonPositiveWeight : Error::InvalidArgument};
  }
  return {q.value().to_double(), {}, Error::FixedOverflow};
}

}  // namespace curvestep::host
