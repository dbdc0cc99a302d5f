// SPDX-License-Identifier: MIT
// WireLayout: a fixed-field message described once, as the list of its members in wire order;
// its encoder, decoder and payload size are derived from that list (as Klipper derives each
// command's encoder from one format string). A message opts in by specialising WireFields:
//
//   template <> struct WireFields<Ack> : WireLayout<&Ack::next_expected, &Ack::credit_end> {};
//
// Wire types follow the members' types: std::uint8_t u8, std::uint16_t u16, std::uint32_t u32,
// std::int32_t i32, double f64 (little-endian, docs/protocol.md "Conventions"), bool u8 (0 or 1),
// an enum its underlying type. Decoding checks each value with valid_wire_value (an overload per
// enum that has a range; a bool must be 0 or 1) and refuses the first bad one as BadPayload at its
// byte offset, a short or long payload as ByteReader does. A message whose fields constrain each
// other overloads `std::size_t first_invalid_field(const M&)` (the byte offset of the first field
// that breaks a rule, or all_fields_valid); decoding refuses it there.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>

#include <curvestep/core/error.hpp>
#include <curvestep/core/result.hpp>
#include <curvestep/protocol/byte_io.hpp>

namespace curvestep::protocol {

/// True for any value of T (the default); enums with a range and bool overload it.
template <class T>
[[nodiscard]] constexpr bool valid_wire_value(const T&) noexcept {
  return true;
}
/// Errors on the wire are never 0 (0 means "no error" in StatusReport).
[[nodiscard]] constexpr bool valid_wire_value(const Error& e) noexcept { return static_cast<std::uint8_t>(e) != 0; }

/// What first_invalid_field returns when the fields agree with each other.
inline constexpr std::size_t all_fields_valid = ~std::size_t{0};

namespace detail {

template <class Pointer>
struct member_pointer;
template <class Message, class Value>
struct member_pointer<Value Message::*> {
  using value = Value;
};

/// The wire type of a member type: itself, an enum's underlying type, bool as std::uint8_t.
template <class T>
using wire_type_of = std::conditional_t<std::is_same_v<T, bool>, std::uint8_t,
                                        typename std::conditional_t<std::is_enum_v<T>, std::underlying_type<T>, std::type_identity<T>>::type>;

template <class W>
constexpr void write_wire(ByteWriter& w, W value) noexcept {
  if constexpr (std::is_same_v<W, std::uint8_t>) w.u8(value);
  else if constexpr (std::is_same_v<W, std::uint16_t>) w.u16(value);
  else if constexpr (std::is_same_v<W, std::uint32_t>) w.u32(value);
  else if constexpr (std::is_same_v<W, std::int32_t>) w.i32(value);
  else if constexpr (std::is_same_v<W, double>) w.f64(value);
  else static_assert(sizeof(W) == 0, "no wire type for this member");
}

template <class W>
constexpr W read_wire(ByteReader& r) noexcept {
  if constexpr (std::is_same_v<W, std::uint8_t>) return r.u8();
  else if constexpr (std::is_same_v<W, std::uint16_t>) return r.u16();
  else if constexpr (std::is_same_v<W, std::uint32_t>) return r.u32();
  else if constexpr (std::is_same_v<W, std::int32_t>) return r.i32();
  else if constexpr (std::is_same_v<W, double>) return r.f64();
  else static_assert(sizeof(W) == 0, "no wire type for this member");
}

template <class T>
constexpr void write_member(ByteWriter& w, const T& value) noexcept {
  write_wire<wire_type_of<T>>(w, static_cast<wire_type_of<T>>(value));
}

template <class T>
constexpr void read_member(ByteReader& r, T& out) noexcept {
  const std::size_t at = r.offset();
  const auto raw = read_wire<wire_type_of<T>>(r);
  if (r.failed()) return;
  if constexpr (std::is_same_v<T, bool>) {
    if (raw > 1) return r.reject_at(Error::BadPayload, at);
    out = raw != 0;
  } else {
    out = static_cast<T>(raw);
    if (!valid_wire_value(out)) r.reject_at(Error::BadPayload, at);
  }
}

}  // namespace detail

/// The fields of a message in wire order (member pointers) and what follows from them.
template <auto... Members>
struct WireLayout {
  /// Payload bytes.
  static constexpr std::size_t size = (std::size_t{0} + ... + sizeof(detail::wire_type_of<typename detail::member_pointer<decltype(Members)>::value>));

  /// Writes the fields of `m` into `out`; the payload's length, or BufferTooSmall.
  template <class M>
  [[nodiscard]] static constexpr Result<std::size_t> encode(const M& m, std::span<std::byte> out) noexcept {
    ByteWriter w(out);
    write(w, m);
    return w.finish();
  }

  /// Reads the fields into an M; BadPayload at the offset of the first bad or missing byte.
  template <class M>
  [[nodiscard]] static constexpr Result<M> decode(std::span<const std::byte> payload) noexcept {
    ByteReader r(payload);
    M m;
    read(r, m);
    if constexpr (requires { first_invalid_field(m); }) {
      if (!r.failed()) {
        const std::size_t at = first_invalid_field(m);
        if (at != all_fields_valid) r.reject_at(Error::BadPayload, at);
      }
    }
    CURVESTEP_CHECK(r.finish());
    return m;
  }

  /// Writes the fields as the head of a longer payload (a message with a variable-length tail).
  template <class M>
  static constexpr void write(ByteWriter& w, const M& m) noexcept {
    (detail::write_member(w, m.*Members), ...);
  }
  /// Reads the fields as the head of a longer payload; the reader records the first bad byte.
  template <class M>
  static constexpr void read(ByteReader& r, M& m) noexcept {
    (detail::read_member(r, m.*Members), ...);
  }
};

/// The layout of message M: specialise as `struct WireFields<M> : WireLayout<&M::a, &M::b> {}`.
template <class M>
struct WireFields;

/// A message with a single description of its fixed fields (WireFields<M> is defined).
template <class M>
concept DescribedMessage = requires { WireFields<M>::size; };

}  // namespace curvestep::protocol
