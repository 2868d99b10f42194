#pragma once
// What the cell orderings share (cell_order.cpp: the heuristics; cell_order_exact.cpp: the exact
// search): the memoised transits with their crossing penalty, and the best variants of an order.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <unordered_map>

#include "swath/planning/cell_order.hpp"

namespace swath::planning::cell_order_detail {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

// std::popcount without the POPCNT instruction (the build targets plain x86-64) is a call into
// libgcc, ~2 % of a plan's instructions from the ordering's inner loop; inline, and most masks
// are 0.
inline int bits_set(std::uint64_t x) {
  if (x == 0) return 0;
  x = x - ((x >> 1) & 0x5555555555555555ull);
  x = (x & 0x3333333333333333ull) + ((x >> 2) & 0x3333333333333333ull);
  x = (x + (x >> 4)) & 0x0f0f0f0f0f0f0f0full;
  return int((x * 0x0101010101010101ull) >> 56);
}

// A transit's length `d` with its penalty: `weight` for each cell still to be flown whose lanes it
// crosses (`crossed_unflown`). One expression for every search, so that they agree bit for bit.
inline double penalised(double d, double weight, std::uint64_t crossed_unflown) {
  return d * (1 + weight * bits_set(crossed_unflown));
}

// Memoised transit lengths between every entry/exit point and home: the metric may be a routed
// shortest path, far dearer than the searches that query it.
class Transit {
 public:
  /// `memoise`: keep exit-to-entry lengths (an n² table) for searches that ask again and again.
  explicit Transit(const CellOrderProblem& p, bool memoise = true) : p_(p), memoise_(memoise) {
    std::size_t offset = 0;
    for (const auto& cell : p.cells) {
      base_.push_back(offset);
      offset += cell.size();
    }
    const std::size_t n = offset;
    home_to_entry_.resize(n);
    exit_to_home_.resize(n);
    // Every transition in a table where that is small; beyond, only the ones asked, hashed: a
    // concave area of 18,000 one-lane runs (a star) asked for ~10^10 entries and ran out of
    // memory, while its search asks for a few per run.
    dense_ = n <= kDenseVariants;
    if (memoise_ && dense_) exit_to_entry_.assign(n * n, -1.0);
    if (memoise_ && dense_ && p.crossed) crossed_.assign(n * n, kUnknown);
    for (std::size_t c = 0; c < p.cells.size(); ++c)
      for (std::size_t v = 0; v < p.cells[c].size(); ++v) {
        home_to_entry_[base_[c] + v] = p.distance(p.home, p.cells[c][v].entry);
        exit_to_home_[base_[c] + v] = p.distance(p.cells[c][v].exit, p.home);
      }
    size_ = n;
  }
  double from_home(std::size_t c, std::size_t v) const { return home_to_entry_[base_[c] + v]; }
  double to_home(std::size_t c, std::size_t v) const { return exit_to_home_[base_[c] + v]; }
  double between(std::size_t c1, std::size_t v1, std::size_t c2, std::size_t v2) {
    if (!memoise_) return p_.distance(p_.cells[c1][v1].exit, p_.cells[c2][v2].entry);
    const std::size_t at = (base_[c1] + v1) * size_ + base_[c2] + v2;
    double& d = dense_ ? exit_to_entry_[at] : sparse_.try_emplace(at).first->second.length_m;
    if (d < 0) d = p_.distance(p_.cells[c1][v1].exit, p_.cells[c2][v2].entry);
    return d;
  }
  /// The cells whose lanes the transit crosses (0 without problem.crossed).
  std::uint64_t crossed(std::size_t c1, std::size_t v1, std::size_t c2, std::size_t v2) {
    if (!p_.crossed) return 0;
    if (!memoise_) return p_.crossed(p_.cells[c1][v1].exit, p_.cells[c2][v2].entry);
    const std::size_t at = (base_[c1] + v1) * size_ + base_[c2] + v2;
    std::uint64_t& m = dense_ ? crossed_[at] : sparse_.try_emplace(at).first->second.crossed;
    if (m == kUnknown) m = p_.crossed(p_.cells[c1][v1].exit, p_.cells[c2][v2].entry) & ~kUnknown;
    return m;
  }
  /// At most cost(c1, v1, c2, v2, unflown), without asking the metric: the cost where known, the
  /// length without the penalty where only that is known (the penalty only adds, for
  /// `crossing_weight` >= 0), else the straight length less 1e-12 of it. Precondition:
  /// `distance_at_least_straight` (the margin covers a routed length's rounding below the
  /// straight one) and `crossing_weight` >= 0.
  double lower_cost(std::size_t c1, std::size_t v1, std::size_t c2, std::size_t v2,
                    std::uint64_t unflown) const {
    if (memoise_) {
      const std::size_t at = (base_[c1] + v1) * size_ + base_[c2] + v2;
      Known known;
      if (dense_) {
        known.length_m = exit_to_entry_[at];
        if (p_.crossed) known.crossed = crossed_[at];
      } else if (const auto it = sparse_.find(at); it != sparse_.end()) {
        known = it->second;
      }
      if (known.length_m >= 0) {
        if (!p_.crossed || known.crossed == kUnknown) return known.length_m;
        return penalised(known.length_m, p_.crossing_weight, known.crossed & unflown);
      }
    }
    return geometry::distance(p_.cells[c1][v1].exit, p_.cells[c2][v2].entry) * (1 - 1e-12);
  }
  /// The least of before[u] + lower_cost(c1, u, c2, v2, unflown) + internal_m over u < count,
  /// summed and compared in that order (a layer of VariantTable::cannot_win()).
  double least_through(const double* before, std::size_t c1, std::size_t count, std::size_t c2,
                       std::size_t v2, std::uint64_t unflown, double internal_m) const {
    double best = kInf;
    if (!memoise_ || !dense_) {  // lower_cost() asks the memo entry by entry
      for (std::size_t u = 0; u < count; ++u)
        best = std::min(best, before[u] + lower_cost(c1, u, c2, v2, unflown) + internal_m);
      return best;
    }
    const bool crossings = bool(p_.crossed);
    std::size_t at = base_[c1] * size_ + base_[c2] + v2;  // (base_[c1] + u) * size_ + ...
    for (std::size_t u = 0; u < count; ++u, at += size_) {
      const double d = exit_to_entry_[at];
      double low = 0;
      if (d < 0)
        low = geometry::distance(p_.cells[c1][u].exit, p_.cells[c2][v2].entry) * (1 - 1e-12);
      else if (!crossings || crossed_[at] == kUnknown)
        low = d;
      else
        low = penalised(d, p_.crossing_weight, crossed_[at] & unflown);
      best = std::min(best, before[u] + low + internal_m);
    }
    return best;
  }
  /// Transit length plus its penalty with the cells in `unflown` still to be flown.
  double cost(std::size_t c1, std::size_t v1, std::size_t c2, std::size_t v2,
              std::uint64_t unflown) {
    const double d = between(c1, v1, c2, v2);
    if (!p_.crossed) return d;
    return penalised(d, p_.crossing_weight, crossed(c1, v1, c2, v2) & unflown);
  }

 private:
  const CellOrderProblem& p_;
  bool memoise_;
  std::vector<std::size_t> base_;
  std::vector<double> home_to_entry_, exit_to_home_, exit_to_entry_;
  // Bit 63 marks "not yet asked": cell 63 never counts (the documented limit is cells below 64).
  static constexpr std::uint64_t kUnknown = std::uint64_t{1} << 63;
  std::vector<std::uint64_t> crossed_;
  /// Up to this many variants in all, the transitions' tables are dense (2 x 32 MB at most).
  static constexpr std::size_t kDenseVariants = 2048;
  struct Known {
    double length_m = -1;              ///< < 0: not asked
    std::uint64_t crossed = kUnknown;  ///< kUnknown: not asked
  };
  bool dense_ = true;
  std::unordered_map<std::size_t, Known> sparse_;  ///< beyond kDenseVariants: by index
  std::size_t size_ = 0;
};

inline std::uint64_t bit(std::size_t cell) {
  return cell < 63 ? std::uint64_t{1} << cell : 0;
}

// Best variants for a fixed order of cells: shortest path through a layered graph, one layer per
// position. Layer k depends only on the cells at positions up to k and on the set of cells after
// k (the crossing penalty), so an order that differs from the last one only from position `from`
// on keeps that one's layers before `from`: the local search's moves change a stretch of at most
// kReach + 1 positions, and recomputing from there instead of from the start halves its work
// with the same sums in the same order (the same objective, bit for bit).
class VariantTable {
 public:
  /// Fills the layers of `order` from position `from` (layers before it are kept from the last
  /// call, whose order had the same cells there); returns the objective. Gives up (returns
  /// infinity, the layers left unfinished) once the objective is certain to be at least
  /// `give_up_m`: transits, penalties and internal lengths are never negative, so a layer's least
  /// cost plus the least internal lengths of the cells after it bound the objective from below
  /// (the margin covers the rounding of adding them in another order).
  ///
  /// `tail` (optional): a table whose suffix() holds the costs of the rest of an order that has
  /// the same cells as `order` from position `check_at` on (the local search's current order,
  /// `check_at` the first position after those a move changes). Once layer `check_at` is filled,
  /// its costs plus the tail's are the objective up to rounding (the same sums, added from the
  /// other end): when that is clearly at least `give_up_m` the fill gives up there, where the
  /// layers after it would have shown the same (the margin is far above the rounding of ~10^3
  /// additions). Gives up only where the full fill's objective is at least `give_up_m`.
  double fill(const CellOrderProblem& p, Transit& t, const std::vector<std::size_t>& order,
              std::size_t from, double give_up_m = kInf, const VariantTable* tail = nullptr,
              std::size_t check_at = std::size_t(-1)) {
    const std::size_t n = order.size();
    if (n == 0) return 0;
    cost_.resize(n * kMaxVariants);
    from_.resize(n * kMaxVariants);
    // Only the entries after `from` are read below, so only those are recomputed (the rest
    // stay as they were: a candidate's table is the current one's up to `from`).
    after_.resize(n + 1);  // cells flown after position k
    after_[n] = 0;
    for (std::size_t k = n; k-- > from;) after_[k] = after_[k + 1] | bit(order[k]);
    const bool may_give_up = give_up_m < kInf && p.crossing_weight >= 0;
    if (may_give_up) {
      rest_.resize(n + 1);  // least internal lengths of the cells after position k - 1
      rest_[n] = 0.0;
      for (std::size_t k = n; k-- > from;) {
        double least = kInf;
        for (const CellVariant& v : p.cells[order[k]]) least = std::min(least, v.internal_m);
        rest_[k] = rest_[k + 1] + least;
      }
    }
    const double margin_m = 1e-9 * (1 + std::abs(give_up_m));
    for (std::size_t k = from; k < n; ++k) {
      const std::size_t cell = order[k];
      const auto& variants = p.cells[cell];
      double* layer = &cost_[k * kMaxVariants];
      std::size_t* came_from = &from_[k * kMaxVariants];
      if (k == 0) {
        for (std::size_t v = 0; v < variants.size(); ++v) {
          layer[v] = t.from_home(cell, v) + variants[v].internal_m;
          came_from[v] = 0;
        }
      } else {
        const std::size_t b = order[k - 1], before_count = p.cells[b].size();
        const double* before = layer - kMaxVariants;
        const std::uint64_t unflown = after_[k + 1];
        for (std::size_t v = 0; v < variants.size(); ++v) {
          const double internal = variants[v].internal_m;
          double best = kInf;
          std::size_t came = 0;
          for (std::size_t u = 0; u < before_count; ++u) {
            const double c = before[u] + t.cost(b, u, cell, v, unflown) + internal;
            if (c < best) {
              best = c;
              came = u;
            }
          }
          layer[v] = best;
          came_from[v] = came;
        }
      }
      if (may_give_up) {
        double least = kInf;
        for (std::size_t v = 0; v < variants.size(); ++v)
          least = std::min(least, cost_[k * kMaxVariants + v]);
        if (least + rest_[k + 1] - margin_m >= give_up_m) return kInf;
      }
      if (tail && k == check_at && may_give_up) {
        double whole = kInf;
        for (std::size_t v = 0; v < variants.size(); ++v)
          whole =
              std::min(whole, cost_[k * kMaxVariants + v] + tail->rest_cost_[k * kMaxVariants + v]);
        if (whole - margin_m >= give_up_m) return kInf;
      }
    }
    last_ = 0;
    double best_cost = kInf;
    for (std::size_t v = 0; v < p.cells[order[n - 1]].size(); ++v) {
      const double c = cost_[(n - 1) * kMaxVariants + v] + t.to_home(order[n - 1], v);
      if (c < best_cost) {
        best_cost = c;
        last_ = v;
      }
    }
    return best_cost;
  }
  /// This table's layers before `from` made `other`'s (what fill() from `from` keeps): the
  /// local search's copy of the current table for each candidate, without the layers it refills.
  void keep_layers_of(const VariantTable& other, std::size_t from) {
    cost_.resize(other.cost_.size());
    from_.resize(other.from_.size());
    const auto count = std::ptrdiff_t(std::min(from * kMaxVariants, other.cost_.size()));
    std::copy(other.cost_.begin(), other.cost_.begin() + count, cost_.begin());
    std::copy(other.from_.begin(), other.from_.begin() + count, from_.begin());
  }
  /// The cost of the rest of `order` (this table's last filled order, filled whole) after each
  /// layer's variant: transits on (with the penalties of the cells still after them), the later
  /// cells' internal lengths and the leg home. What fill()'s `tail` reads.
  void suffix(const CellOrderProblem& p, Transit& t, const std::vector<std::size_t>& order) {
    const std::size_t n = order.size();
    rest_cost_.assign(n * kMaxVariants, kInf);
    after_all_.assign(n + 1, 0);
    for (std::size_t k = n; k-- > 0;) after_all_[k] = after_all_[k + 1] | bit(order[k]);
    if (n == 0) return;
    for (std::size_t v = 0; v < p.cells[order[n - 1]].size(); ++v)
      rest_cost_[(n - 1) * kMaxVariants + v] = t.to_home(order[n - 1], v);
    std::uint64_t after = 0;  // cells flown after position k + 1
    for (std::size_t k = n - 1; k-- > 0;) {
      const auto& next = p.cells[order[k + 1]];
      for (std::size_t u = 0; u < p.cells[order[k]].size(); ++u) {
        double best = kInf;
        for (std::size_t v = 0; v < next.size(); ++v)
          best = std::min(best, t.cost(order[k], u, order[k + 1], v, after) + next[v].internal_m +
                                    rest_cost_[(k + 1) * kMaxVariants + v]);
        rest_cost_[k * kMaxVariants + u] = best;
      }
      after |= bit(order[k + 1]);
    }
  }
  /// Whether `order`, a candidate of the local search whose layers before `from` this table holds
  /// (keep_layers_of()) and whose cells from `check_at` on are those of the order `tail` last
  /// took the suffix() of, certainly cannot reach below `give_up_m`: its layers `from` to
  /// `check_at` with the transits' lower bounds (Transit::lower_cost(), no metric asked) plus
  /// the tail's costs, less fill()'s margin. Each such layer is at most fill()'s (the same sums
  /// of terms no larger, rounding is monotone), so fill() would give up at `check_at` (or
  /// before) too: the same candidates are kept, but the rejected ones ask no routed transit.
  /// Precondition: as for Transit::lower_cost(); from < check_at < order.size().
  bool cannot_win(const CellOrderProblem& p, const Transit& t,
                  const std::vector<std::size_t>& order, std::size_t from, std::size_t check_at,
                  double give_up_m, const VariantTable& tail) {
    const std::size_t layers = check_at - from + 1;
    low_.assign(layers * kMaxVariants, kInf);
    masks_.resize(layers);
    std::uint64_t after = tail.after_all_[check_at + 1];  // the cells after position k
    for (std::size_t k = check_at + 1; k-- > from;) {
      masks_[k - from] = after;
      after |= bit(order[k]);
    }
    for (std::size_t k = from; k <= check_at; ++k) {
      const std::size_t c = order[k];
      const auto& variants = p.cells[c];
      double* layer = &low_[(k - from) * kMaxVariants];
      if (k == 0) {
        for (std::size_t v = 0; v < variants.size(); ++v)
          layer[v] = t.from_home(c, v) + variants[v].internal_m;
        continue;
      }
      const std::size_t b = order[k - 1], before_count = p.cells[b].size();
      const double* before = k == from ? &cost_[(k - 1) * kMaxVariants] : layer - kMaxVariants;
      const std::uint64_t unflown = masks_[k - from];
      for (std::size_t v = 0; v < variants.size(); ++v)
        layer[v] = t.least_through(before, b, before_count, c, v, unflown, variants[v].internal_m);
    }
    double whole = kInf;
    for (std::size_t v = 0; v < p.cells[order[check_at]].size(); ++v)
      whole = std::min(whole, low_[(check_at - from) * kMaxVariants + v] +
                                  tail.rest_cost_[check_at * kMaxVariants + v]);
    const double margin_m = 1e-9 * (1 + std::abs(give_up_m));
    return whole - margin_m >= give_up_m;
  }
  /// The visits of the last filled order.
  std::vector<CellVisit> visits(const std::vector<std::size_t>& order) const {
    std::vector<CellVisit> out(order.size());
    std::size_t best = last_;
    for (std::size_t k = order.size(); k-- > 0;) {
      out[k] = {order[k], best};
      best = from_[k * kMaxVariants + best];
    }
    return out;
  }

 private:
  static constexpr std::size_t kMaxVariants = 4;
  std::vector<double> cost_;
  std::vector<std::size_t> from_;
  std::vector<std::uint64_t> after_;
  std::vector<double> rest_;
  std::vector<double> rest_cost_;         ///< suffix(): per layer and variant
  std::vector<std::uint64_t> after_all_;  ///< suffix(): the cells from position k on
  std::vector<double> low_;               ///< cannot_win()'s layers
  std::vector<std::uint64_t> masks_;      ///< cannot_win(): the cells after each of its layers
  std::size_t last_ = 0;
};

inline CellOrder best_variants(const CellOrderProblem& p, Transit& t,
                               const std::vector<std::size_t>& order) {
  CellOrder result;
  if (order.empty()) {
    result.length_m = 0;
    return result;
  }
  VariantTable table;
  result.objective_m = table.fill(p, t, order, 0);
  result.visits = table.visits(order);
  return result;
}

// The order's real length and crossings beside the objective the search found.
inline CellOrder finished(const CellOrderProblem& p, CellOrder order) {
  const CellOrder e = evaluate_order(p, order.visits);
  order.length_m = e.length_m;
  order.crossings = e.crossings;
  return order;
}

}  // namespace swath::planning::cell_order_detail
