#pragma once
// Internal to the router (visibility.cpp, visibility_search.cpp): the table of which corners see
// each other, shared by a router and its copies.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>

#include "swath/geometry/visibility.hpp"

namespace swath::geometry {

// Threads that share the tables may test a pair at once: both find the same answer (the same exact
// tests, with or without a fan), so either store stands. A fan and a chunk of the table are
// published whole (release) and only the first one made is kept. The table comes in chunks made
// when first written: a search asks about the pairs near its path only, and a full table of 10^4
// nodes would be 10^8 bytes.
struct VisibilityRouter::NodeTables {
  static constexpr std::size_t kChunk = 4096;  ///< pairs per chunk of one row (the last: the rest)
  using Chunk = std::atomic<signed char>;
  explicit NodeTables(std::size_t n)
      : nodes(n),
        per_row((n + kChunk - 1) / kChunk),
        chunks(new std::atomic<Chunk*>[n * per_row]),
        fans(new std::atomic<Fan*>[n]),
        hidden(new std::atomic<Bits*>[n * per_row]) {
    for (std::size_t k = 0; k < n * per_row; ++k) {
      chunks[k].store(nullptr, std::memory_order_relaxed);
      hidden[k].store(nullptr, std::memory_order_relaxed);
    }
    for (std::size_t k = 0; k < n; ++k) fans[k].store(nullptr, std::memory_order_relaxed);
  }
  ~NodeTables() {
    for (std::size_t k = 0; k < nodes * per_row; ++k) {
      delete[] chunks[k].load(std::memory_order_acquire);
      delete[] hidden[k].load(std::memory_order_acquire);
    }
    for (std::size_t k = 0; k < nodes; ++k) delete fans[k].load(std::memory_order_acquire);
  }
  NodeTables(const NodeTables&) = delete;
  NodeTables& operator=(const NodeTables&) = delete;
  /// Whether i sees j: kUnknown until asked; null where nothing of its chunk has been asked.
  const Chunk* find(std::size_t i, std::size_t j) const {
    const Chunk* chunk = chunks[i * per_row + j / kChunk].load(std::memory_order_acquire);
    return chunk ? chunk + j % kChunk : nullptr;
  }
  /// Chunk c of row i (its pairs c kChunk, ...), null while nothing of it has been asked.
  const Chunk* chunk_of(std::size_t i, std::size_t c) const {
    return chunks[i * per_row + c].load(std::memory_order_acquire);
  }
  Chunk& at(std::size_t i, std::size_t j) {
    std::atomic<Chunk*>& slot = chunks[i * per_row + j / kChunk];
    Chunk* chunk = slot.load(std::memory_order_acquire);
    if (!chunk) {
      // Only as long as the row (below kChunk nodes): rows of 4096 bytes each, of which a search
      // reads the first few hundred, all fell on the same few sets of the caches.
      const std::size_t size = std::min(kChunk, nodes - j / kChunk * kChunk);
      auto made = std::make_unique<Chunk[]>(size);
      for (std::size_t k = 0; k < size; ++k) made[k].store(kUnknown, std::memory_order_relaxed);
      if (slot.compare_exchange_strong(chunk, made.get(), std::memory_order_acq_rel,
                                       std::memory_order_acquire))
        chunk = made.release();  // kept; otherwise `chunk` is the one another thread published
    }
    return chunk[j % kChunk];
  }
  /// The pairs of row i known not to see each other, as bits: a search going on from a node skips
  /// them a word (64 nodes) at a time rather than measuring a leg to each open node first.
  using Bits = std::atomic<std::uint64_t>;
  static constexpr std::size_t kWords = kChunk / 64;  ///< words per chunk of a row
  /// Chunk c of row i's bits (bit u % kChunk of word (u % kChunk) / 64: node u hidden from i),
  /// null while no pair of it is known hidden.
  const Bits* hidden_of(std::size_t i, std::size_t c) const {
    return hidden[i * per_row + c].load(std::memory_order_acquire);
  }
  /// Node j known not to see node i (its answer already stored in the table): its bit in row i.
  void mark_hidden(std::size_t i, std::size_t j) {
    std::atomic<Bits*>& slot = hidden[i * per_row + j / kChunk];
    Bits* bits = slot.load(std::memory_order_acquire);
    if (!bits) {
      const std::size_t words = (std::min(kChunk, nodes - j / kChunk * kChunk) + 63) / 64;
      auto made = std::make_unique<Bits[]>(words);
      for (std::size_t k = 0; k < words; ++k) made[k].store(0, std::memory_order_relaxed);
      if (slot.compare_exchange_strong(bits, made.get(), std::memory_order_acq_rel,
                                       std::memory_order_acquire))
        bits = made.release();  // kept; otherwise `bits` is the one another thread published
    }
    bits[j % kChunk / 64].fetch_or(std::uint64_t{1} << (j % 64), std::memory_order_relaxed);
  }
  std::size_t nodes, per_row;
  std::unique_ptr<std::atomic<Chunk*>[]> chunks;  ///< per row, per chunk of it
  std::unique_ptr<std::atomic<Fan*>[]> fans;      ///< per node, null until made
  std::unique_ptr<std::atomic<Bits*>[]> hidden;   ///< per row, per chunk of it
};

}  // namespace swath::geometry
