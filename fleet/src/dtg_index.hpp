#pragma once
// Adjacency of a DTG for the forecaster: parents (backward edges the signatures follow), what a
// node spawned, which sync nodes await a task, and what a task's "next" is (docs/swath-fleet.md).

#include <cstddef>
#include <vector>

#include "swath/fleet/dtg.hpp"

namespace swath::fleet::detail {

/// A node index as a vector position.
constexpr std::size_t at(int i) {
  return static_cast<std::size_t>(i);
}

struct DtgIndex {
  explicit DtgIndex(const Dtg& g);
  /// Sources of spawn edges into a task node, of sync edges into a sync node.
  std::vector<std::vector<int>> parents;
  std::vector<std::vector<int>> spawned;     ///< task nodes a node's spawn edges lead to
  std::vector<std::vector<int>> awaited_by;  ///< sync nodes awaiting a task node
  std::vector<std::vector<int>> cancelled;   ///< task nodes a node's cancel edges lead to
  /// Per task node: whether its next is known (a sync node awaits it and every task that sync
  /// awaits has ended, so the waiter went on) and the located task nodes its waiter spawned
  /// after that sync, up to its next sync (one iteration).
  std::vector<char> next_known;
  std::vector<std::vector<int>> next;
};

}  // namespace swath::fleet::detail
