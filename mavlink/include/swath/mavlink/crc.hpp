#pragma once
// The MAVLink checksum: CRC-16/MCRF4XX ("X.25" in MAVLink's documents; polynomial 0x1021 reflected,
// initial value 0xFFFF, no final XOR). A frame's checksum covers every byte after the start marker
// up to the end of the payload, then the message's CRC_EXTRA byte (crc_extra.hpp), which ties a
// frame to the exact field layout both ends compiled in.

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace swath::mavlink {

/// A running CRC-16/MCRF4XX. `Crc16{}.add(bytes).value()`; check value of "123456789" is 0x6F91.
class Crc16 {
 public:
  constexpr Crc16& add(std::uint8_t byte) {
    std::uint8_t t = static_cast<std::uint8_t>(byte ^ (value_ & 0xFF));
    t = static_cast<std::uint8_t>(t ^ (t << 4));
    value_ = static_cast<std::uint16_t>((value_ >> 8) ^ (t << 8) ^ (t << 3) ^ (t >> 4));
    return *this;
  }
  constexpr Crc16& add(const std::uint8_t* bytes, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) add(bytes[i]);
    return *this;
  }
  constexpr Crc16& add(std::string_view text) {
    for (char c : text) add(static_cast<std::uint8_t>(c));
    return *this;
  }
  constexpr std::uint16_t value() const { return value_; }

 private:
  std::uint16_t value_ = 0xFFFF;
};

}  // namespace swath::mavlink
