#pragma once
// Field-by-field jobs over a message's `fields(v)` list (messages.hpp): payload lengths, the
// CRC_EXTRA seed, little-endian encoding with MAVLink 2's trailing-zero truncation, and decoding
// with zero fill of a truncated payload (MAVLink 2 senders drop trailing zero bytes; extension
// fields a sender does not know arrive as zeros).

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <type_traits>

#include "swath/mavlink/crc.hpp"

namespace swath::mavlink {

namespace detail {

template <class T>
struct FieldShape {  // a scalar field
  using Element = T;
  static constexpr std::size_t count = 0;  // MAVLink's array length; 0 = not an array
};
template <class T, std::size_t N>
struct FieldShape<std::array<T, N>> {
  using Element = T;
  static constexpr std::size_t count = N;
};

/// The C type name MAVLink's CRC_EXTRA seed hashes.
template <class T>
constexpr std::string_view type_name() {
  if constexpr (std::is_same_v<T, char>)
    return "char";
  else if constexpr (std::is_same_v<T, std::uint8_t>)
    return "uint8_t";
  else if constexpr (std::is_same_v<T, std::int8_t>)
    return "int8_t";
  else if constexpr (std::is_same_v<T, std::uint16_t>)
    return "uint16_t";
  else if constexpr (std::is_same_v<T, std::int16_t>)
    return "int16_t";
  else if constexpr (std::is_same_v<T, std::uint32_t>)
    return "uint32_t";
  else if constexpr (std::is_same_v<T, std::int32_t>)
    return "int32_t";
  else if constexpr (std::is_same_v<T, std::uint64_t>)
    return "uint64_t";
  else if constexpr (std::is_same_v<T, std::int64_t>)
    return "int64_t";
  else if constexpr (std::is_same_v<T, float>)
    return "float";
  else if constexpr (std::is_same_v<T, double>)
    return "double";
  else
    static_assert(sizeof(T) == 0, "not a MAVLink field type");
}

template <class T>
constexpr std::size_t field_bytes() {
  using Shape = FieldShape<T>;
  return sizeof(typename Shape::Element) * (Shape::count == 0 ? 1 : Shape::count);
}

struct LengthCounter {
  std::size_t base = 0, all = 0;
  template <class T>
  constexpr void field(const T&, std::string_view) {
    base += field_bytes<T>();
    all += field_bytes<T>();
  }
  template <class T>
  constexpr void extension(const T&, std::string_view) {
    all += field_bytes<T>();
  }
};

/// CRC_EXTRA as MAVLink's generators compute it: the message name, then per base field (extensions
/// excluded) its element type, its name and, for arrays, the length as one byte; both bytes folded.
struct CrcExtraSeed {
  Crc16 crc;
  template <class T>
  constexpr void field(const T&, std::string_view name) {
    using Shape = FieldShape<T>;
    crc.add(type_name<typename Shape::Element>()).add(" ").add(name).add(" ");
    if constexpr (Shape::count != 0) crc.add(static_cast<std::uint8_t>(Shape::count));
  }
  template <class T>
  constexpr void extension(const T&, std::string_view) {}
};

template <class E>
constexpr void put_scalar(std::uint8_t* out, E value) {
  if constexpr (std::is_same_v<E, float>) {
    put_scalar(out, std::bit_cast<std::uint32_t>(value));
  } else if constexpr (std::is_same_v<E, double>) {
    put_scalar(out, std::bit_cast<std::uint64_t>(value));
  } else {
    using U = std::make_unsigned_t<E>;
    const U u = static_cast<U>(value);
    for (std::size_t i = 0; i < sizeof(E); ++i) out[i] = static_cast<std::uint8_t>(u >> (8 * i));
  }
}

template <class E>
constexpr E get_scalar(const std::uint8_t* in) {
  if constexpr (std::is_same_v<E, float>) {
    return std::bit_cast<float>(get_scalar<std::uint32_t>(in));
  } else if constexpr (std::is_same_v<E, double>) {
    return std::bit_cast<double>(get_scalar<std::uint64_t>(in));
  } else {
    using U = std::make_unsigned_t<E>;
    U u = 0;
    for (std::size_t i = 0; i < sizeof(E); ++i) u = static_cast<U>(u | (U(in[i]) << (8 * i)));
    return static_cast<E>(u);
  }
}

struct Writer {
  std::uint8_t* out;
  std::size_t pos = 0;
  template <class T>
  constexpr void field(const T& value, std::string_view) {
    using Shape = FieldShape<T>;
    using E = typename Shape::Element;
    if constexpr (Shape::count == 0) {
      put_scalar<E>(out + pos, value);
      pos += sizeof(E);
    } else {
      for (const E& e : value) {
        put_scalar<E>(out + pos, e);
        pos += sizeof(E);
      }
    }
  }
  template <class T>
  constexpr void extension(const T& value, std::string_view name) {
    field(value, name);
  }
};

struct Reader {
  const std::uint8_t* in;
  std::size_t length;  // bytes received; the rest reads as zero
  std::size_t pos = 0;
  template <class E>
  constexpr E next() {
    std::array<std::uint8_t, sizeof(E)> bytes{};
    for (std::size_t i = 0; i < sizeof(E); ++i)
      bytes[i] = pos + i < length ? in[pos + i] : std::uint8_t{0};
    pos += sizeof(E);
    return get_scalar<E>(bytes.data());
  }
  template <class T>
  constexpr void field(T& value, std::string_view) {
    using Shape = FieldShape<T>;
    using E = typename Shape::Element;
    if constexpr (Shape::count == 0) {
      value = next<E>();
    } else {
      for (E& e : value) e = next<E>();
    }
  }
  template <class T>
  constexpr void extension(T& value, std::string_view name) {
    field(value, name);
  }
};

}  // namespace detail

/// Bytes of M's payload without extensions (what MAVLink 1 carries) and with them.
template <class M>
constexpr std::size_t base_payload_length() {
  M m{};
  detail::LengthCounter c;
  m.fields(c);
  return c.base;
}
template <class M>
constexpr std::size_t max_payload_length() {
  M m{};
  detail::LengthCounter c;
  m.fields(c);
  return c.all;
}

/// M's CRC_EXTRA byte.
template <class M>
constexpr std::uint8_t crc_extra() {
  M m{};
  detail::CrcExtraSeed seed;
  seed.crc.add(M::kName).add(" ");
  m.fields(seed);
  const std::uint16_t v = seed.crc.value();
  return static_cast<std::uint8_t>((v & 0xFF) ^ (v >> 8));
}

/// Writes M's full payload (max_payload_length<M>() bytes) into `out`; returns the length MAVLink 2
/// sends: trailing zero bytes dropped, at least 1.
template <class M>
constexpr std::size_t encode_payload(const M& message, std::uint8_t* out) {
  M copy = message;  // fields() lists members by reference; the writer only reads them
  detail::Writer w{out};
  copy.fields(w);
  std::size_t n = w.pos;
  while (n > 1 && out[n - 1] == 0) --n;
  return n;
}

/// M from a payload of `length` bytes (shorter than M's: the rest is zero; longer: ignored).
template <class M>
constexpr M decode_payload(const std::uint8_t* payload, std::size_t length) {
  M m{};
  detail::Reader r{payload, length};
  m.fields(r);
  return m;
}

}  // namespace swath::mavlink
