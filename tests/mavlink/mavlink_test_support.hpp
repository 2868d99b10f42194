#pragma once
// Random MAVLink messages and frames for the codec tests, the oracle test and the bench.
#include <bit>
#include <cstdint>
#include <random>
#include <string_view>
#include <type_traits>
#include <vector>

#include "swath/mavlink/frame.hpp"
#include "swath/mavlink/messages.hpp"

namespace swath::mavlink::test {

// Fills every field with random bits (each field zero with probability `zero_p`, so that payloads
// end in zeros and get truncated); char arrays get printable text ended by a NUL or not.
struct Randomizer {
  std::mt19937_64& rng;
  double zero_p;
  bool zero() { return std::uniform_real_distribution<double>(0, 1)(rng) < zero_p; }
  template <class E>
  E scalar() {
    if constexpr (std::is_same_v<E, float>) {
      return std::bit_cast<float>(static_cast<std::uint32_t>(rng()));
    } else if constexpr (std::is_same_v<E, double>) {
      return std::bit_cast<double>(static_cast<std::uint64_t>(rng()));
    } else {
      return static_cast<E>(rng());
    }
  }
  template <class T>
  void field(T& value, std::string_view) {
    using Shape = detail::FieldShape<T>;
    using E = typename Shape::Element;
    const bool z = zero();
    if constexpr (Shape::count == 0) {
      value = z ? E{} : scalar<E>();
    } else if constexpr (std::is_same_v<E, char>) {
      value = {};
      const std::size_t n = z ? 0 : rng() % (value.size() + 1);
      for (std::size_t i = 0; i < n; ++i) value[i] = static_cast<char>('!' + rng() % 94);
    } else {
      for (E& e : value) e = z ? E{} : scalar<E>();
    }
  }
  template <class T>
  void extension(T& value, std::string_view name) {
    field(value, name);
  }
};

template <class M>
M random_message(std::mt19937_64& rng, double zero_p) {
  M m{};
  Randomizer r{rng, zero_p};
  m.fields(r);
  return m;
}

// The whole payload, extensions included, untruncated: equal bytes = equal messages, NaNs too.
template <class M>
std::vector<std::uint8_t> full_payload(const M& m) {
  std::vector<std::uint8_t> bytes(max_payload_length<M>());
  M copy = m;
  detail::Writer w{bytes.data()};
  copy.fields(w);
  return bytes;
}

// A random message of a random type; ids below 256 go as MAVLink 1 one time in four.
inline Frame random_frame(std::mt19937_64& rng, std::uint8_t seq) {
  const auto messages = known_messages();
  const std::uint32_t id = messages[rng() % messages.size()].id;
  Frame frame;
  for_each_message([&](auto sample) {
    using M = decltype(sample);
    if (M::kId != id) return;
    frame = pack(random_message<M>(rng, 0.3),
                 FrameHeader{seq, static_cast<std::uint8_t>(1 + rng() % 3), 1});
    if (M::kId < 256 && rng() % 4 == 0) {
      frame.version = 1;
      frame.payload_length = static_cast<std::uint8_t>(base_payload_length<M>());
    }
  });
  return frame;
}

}  // namespace swath::mavlink::test
