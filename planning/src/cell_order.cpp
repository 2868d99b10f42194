#include "swath/planning/cell_order.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <unordered_map>

namespace swath::planning {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// std::popcount without the POPCNT instruction (the build targets plain x86-64) is a call into
// libgcc, ~2 % of a plan's instructions from the ordering's inner loop; inline, and most masks
// are 0.
int bits_set(std::uint64_t x) {
  if (x == 0) return 0;
  x = x - ((x >> 1) & 0x5555555555555555ull);
  x = (x & 0x3333333333333333ull) + ((x >> 2) & 0x3333333333333333ull);
  x = (x + (x >> 4)) & 0x0f0f0f0f0f0f0f0full;
  return int((x * 0x0101010101010101ull) >> 56);
}

// A transit's length `d` with its penalty: `weight` for each cell still to be flown whose lanes it
// crosses (`crossed_unflown`). One expression for every search, so that they agree bit for bit.
double penalised(double d, double weight, std::uint64_t crossed_unflown) {
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

std::uint64_t bit(std::size_t cell) {
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

CellOrder best_variants(const CellOrderProblem& p, Transit& t,
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
CellOrder finished(const CellOrderProblem& p, CellOrder order) {
  const CellOrder e = evaluate_order(p, order.visits);
  order.length_m = e.length_m;
  order.crossings = e.crossings;
  return order;
}

}  // namespace

CellOrder evaluate_order(const CellOrderProblem& p, const std::vector<CellVisit>& visits) {
  CellOrder e;
  e.visits = visits;
  e.length_m = tour_length(p, visits);
  e.objective_m = e.length_m;
  std::uint64_t unflown = 0;
  for (const CellVisit& v : visits) unflown |= bit(v.cell);
  for (std::size_t k = 0; k + 1 < visits.size() && p.crossed; ++k) {
    unflown &= ~bit(visits[k].cell);
    const geometry::Point2 a = p.cells[visits[k].cell][visits[k].variant].exit;
    const geometry::Point2 b = p.cells[visits[k + 1].cell][visits[k + 1].variant].entry;
    const int n = std::popcount(p.crossed(a, b) & unflown & ~bit(visits[k + 1].cell));
    e.crossings += std::size_t(n);
    e.objective_m += p.crossing_weight * n * p.distance(a, b);
  }
  return e;
}

double tour_length(const CellOrderProblem& p, const std::vector<CellVisit>& visits) {
  if (visits.empty()) return 0.0;
  double length = p.distance(p.home, p.cells[visits[0].cell][visits[0].variant].entry);
  for (std::size_t k = 0; k < visits.size(); ++k) {
    const CellVariant& v = p.cells[visits[k].cell][visits[k].variant];
    length += v.internal_m;
    const geometry::Point2 next =
        k + 1 < visits.size() ? p.cells[visits[k + 1].cell][visits[k + 1].variant].entry : p.home;
    length += p.distance(v.exit, next);
  }
  return length;
}

CellOrder exact_cell_order(const CellOrderProblem& p) {
  const std::size_t n = p.cells.size();
  if (n > 16) throw std::invalid_argument("exact_cell_order: more than 16 cells");
  if (n == 0) return {};
  Transit t(p, /*memoise=*/false);  // every transition is asked once, into the tables below
  constexpr std::size_t kMaxVariants = 4;
  const std::size_t states = n * kMaxVariants;
  // Every transition's length and crossed cells first (Held-Karp asks for each of them: every
  // cell is reachable alone), in flat tables: the search below then reads arrays only. Region
  // division orders a share's runs for every share it weighs; with vectors per subset and the
  // memo's checks per transition, 12 runs took ~70 % of a four-drone division's minutes.
  std::vector<double> between(states * states, kInf);
  std::vector<std::uint64_t> crossed(p.crossed ? states * states : 0, 0);
  for (std::size_t c = 0; c < n; ++c)
    for (std::size_t v = 0; v < p.cells[c].size(); ++v)
      for (std::size_t c2 = 0; c2 < n; ++c2) {
        if (c2 == c) continue;
        for (std::size_t v2 = 0; v2 < p.cells[c2].size(); ++v2) {
          const std::size_t at = (c * kMaxVariants + v) * states + c2 * kMaxVariants + v2;
          between[at] = t.between(c, v, c2, v2);
          if (p.crossed) crossed[at] = t.crossed(c, v, c2, v2);
        }
      }
  // cost[mask * states + cell * 4 + variant]: shortest start from home visiting `mask`, ending in
  // that state; parent: the state before (states: none). The same order of updates as a plain
  // loop over every state of every mask (states outside the mask are never reached), so ties
  // keep the same parents. A mask's row is laid (kInf, no parent) only when a state of it is
  // first written (`reached`), and masks never reached are skipped: with the bound below most
  // are, and filling every row (1.5 MB at 12 cells) and scanning it took more than the search of
  // the reached ones. The tables are the thread's, kept between calls (region division orders
  // ~50,000 shares a plan).
  const std::size_t masks = std::size_t{1} << n;
  thread_local std::vector<double> cost;
  thread_local std::vector<std::uint8_t> parent;
  thread_local std::vector<std::uint8_t> reached;
  if (cost.size() < masks * states) {
    cost.resize(masks * states);
    parent.resize(masks * states);
  }
  reached.assign(masks, 0);
  const auto reach = [&](std::size_t mask) {
    if (reached[mask]) return;
    reached[mask] = 1;
    std::fill_n(cost.begin() + std::ptrdiff_t(mask * states), states, kInf);
    std::fill_n(parent.begin() + std::ptrdiff_t(mask * states), states,
                static_cast<std::uint8_t>(states));
  };
  for (std::size_t c = 0; c < n; ++c) {
    reach(std::size_t{1} << c);
    for (std::size_t v = 0; v < p.cells[c].size(); ++v)
      cost[(std::size_t{1} << c) * states + c * kMaxVariants + v] =
          t.from_home(c, v) + p.cells[c][v].internal_m;
  }
  std::vector<double> internal(states, 0.0);
  std::vector<std::size_t> variants(n);
  for (std::size_t c = 0; c < n; ++c) {
    variants[c] = p.cells[c].size();
    for (std::size_t v = 0; v < variants[c]; ++v)
      internal[c * kMaxVariants + v] = p.cells[c][v].internal_m;
  }
  // A bound to prune by: the objective of a good tour (improved(greedy_tour()) below, in the
  // search's own arithmetic), with a margin above its rounding. A state whose cost plus a lower
  // bound on the rest of every tour through it exceeds it is on no optimal tour, nor on a tie of
  // one, and the states an optimal tour passes through, and those that tie them, keep their costs
  // and parents (their predecessors are on an optimal tour too, or give strictly more): the same
  // tour, bit for bit, the search cut to the tours that one does not beat. The rest of a tour
  // enters each cell still to fly once, adding at least its least internal length and its least
  // way in (from home or another cell's exit; a crossing penalty only adds, for a weight >= 0),
  // and comes home once from one of them (`least_home`).
  std::vector<double> least_added(n, kInf), least_home(n, kInf);
  double all_least = 0;
  for (std::size_t c = 0; c < n; ++c) {
    double way_in = kInf;
    for (std::size_t v = 0; v < variants[c]; ++v) {
      const std::size_t s2 = c * kMaxVariants + v;
      least_added[c] = std::min(least_added[c], internal[s2]);
      least_home[c] = std::min(least_home[c], t.to_home(c, v));
      way_in = std::min(way_in, t.from_home(c, v));
      for (std::size_t s = 0; s < states; ++s) way_in = std::min(way_in, between[s * states + s2]);
    }
    least_added[c] += std::max(0.0, way_in);
    all_least += least_added[c];
  }
  const auto greedy_tour = [&] {
    std::vector<std::size_t> tour;
    std::size_t at = states, flown = 0;  // states: at home
    for (std::size_t k = 0; k < n; ++k) {
      double best = kInf;
      std::size_t best_s = states;
      const std::uint64_t unflown_before = ~std::uint64_t{0} & ~flown;
      for (std::size_t c2 = 0; c2 < n; ++c2) {
        if (flown & (std::size_t{1} << c2)) continue;
        for (std::size_t v2 = 0; v2 < variants[c2]; ++v2) {
          const std::size_t s2 = c2 * kMaxVariants + v2;
          double transit = 0;
          if (at == states) {
            transit = t.from_home(c2, v2);
          } else {
            const std::size_t i = at * states + s2;
            transit = between[i];
            if (p.crossed)
              transit = penalised(transit, p.crossing_weight,
                                  crossed[i] & unflown_before & ~(std::uint64_t{1} << c2));
          }
          if (transit + internal[s2] < best) {
            best = transit + internal[s2];
            best_s = s2;
          }
        }
      }
      if (best_s == states) return std::vector<std::size_t>{};  // a cell without variants
      tour.push_back(best_s);
      at = best_s;
      flown |= std::size_t{1} << (best_s / kMaxVariants);
    }
    return tour;
  };
  // The greedy tour's order improved by local search: a block of one or two cells moved to
  // another place, or a run of cells reversed (2-opt), the first move that shortens it kept, until
  // none does; every order flown with its best variants (a shortest path through one layer of
  // variants per position, in the search's own arithmetic: its objective is that of a tour, so
  // at least the optimum's). A bound near the optimum prunes most states: on a four-drone region
  // division's orderings this one was 1.1 % above the optimum on average, moving one cell at a
  // time with the others' variants fixed 5.6 % (the search expanded twice the states); blocks of
  // three as well found bounds as good (1.11 % against 1.12 %) at more cost than they saved.
  //
  // An order differing from the current one from position `from` on keeps its layers before it
  // (the cells after each of them are the same set), and its fill gives up once a layer's least
  // cost plus the least internal lengths of the cells after it reaches the objective to beat
  // (the rest of its tour adds no less: transits and their penalties are never negative here).
  double least_internal[16];
  for (std::size_t c = 0; c < n; ++c) {
    least_internal[c] = kInf;
    for (std::size_t v = 0; v < variants[c]; ++v)
      least_internal[c] = std::min(least_internal[c], internal[c * kMaxVariants + v]);
  }
  using Layers = std::array<std::array<double, kMaxVariants>, 16>;
  const auto fill = [&](const std::array<std::size_t, 16>& order, std::size_t from, Layers& layer,
                        double give_up) {
    double rest = 0;  // the least internal lengths of the cells after position k
    for (std::size_t k = from + 1; k < n; ++k) rest += least_internal[order[k]];
    std::uint64_t flown = 0;  // the cells up to position k
    for (std::size_t k = 0; k < from; ++k) flown |= std::uint64_t{1} << order[k];
    for (std::size_t k = from; k < n; ++k) {
      const std::size_t c = order[k];
      flown |= std::uint64_t{1} << c;
      double least = kInf;
      for (std::size_t v = 0; v < variants[c]; ++v) {
        const std::size_t s2 = c * kMaxVariants + v;
        double best = kInf;
        if (k == 0) {
          best = t.from_home(c, v) + internal[s2];
        } else {
          const std::size_t b = order[k - 1];
          for (std::size_t u = 0; u < variants[b]; ++u) {
            const std::size_t at = (b * kMaxVariants + u) * states + s2;
            double transit = between[at];
            if (p.crossed) transit = penalised(transit, p.crossing_weight, crossed[at] & ~flown);
            best = std::min(best, layer[k - 1][u] + transit + internal[s2]);
          }
        }
        layer[k][v] = best;
        least = std::min(least, best);
      }
      if (k + 1 < n) {
        rest -= least_internal[order[k + 1]];
        if (least + std::max(0.0, rest) >= give_up) return kInf;
      }
    }
    double objective = kInf;
    for (std::size_t v = 0; v < variants[order[n - 1]]; ++v)
      objective = std::min(objective, layer[n - 1][v] + t.to_home(order[n - 1], v));
    return objective;
  };
  const auto improved = [&](const std::vector<std::size_t>& tour) {
    if (tour.empty()) return kInf;
    std::array<std::size_t, 16> order{}, candidate{};
    for (std::size_t k = 0; k < n; ++k) order[k] = tour[k] / kMaxVariants;
    Layers current, trial;
    double objective = fill(order, 0, current, kInf);
    const auto at = [&candidate](std::size_t k) {
      return candidate.begin() + static_cast<std::ptrdiff_t>(k);
    };
    const auto consider = [&](std::size_t from) {
      std::copy_n(current.begin(), from, trial.begin());
      const double o = fill(candidate, from, trial, objective * (1 - 1e-12));
      if (!(o < objective * (1 - 1e-12))) return false;
      objective = o;
      order = candidate;
      current = trial;
      return true;
    };
    // At most 100 passes: each finds a shorter order (at most a few passes are expected).
    for (int pass = 0, better = 1; better && pass < 100; ++pass) {
      better = 0;
      for (std::size_t len = 1; len <= 2 && len < n; ++len)
        for (std::size_t i = 0; i + len <= n; ++i)
          for (std::size_t j = 0; j + len <= n; ++j) {
            if (j == i) continue;
            candidate = order;
            if (j < i)
              std::rotate(at(j), at(i), at(i + len));
            else
              std::rotate(at(i), at(i + len), at(j + len));
            better |= consider(std::min(i, j));
          }
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 2; j < n; ++j) {
          candidate = order;
          std::reverse(at(i), at(j + 1));
          better |= consider(i);
        }
    }
    return objective;
  };
  const double bound = p.crossing_weight >= 0 ? improved(greedy_tour()) * (1 + 1e-9) + 1e-9 : kInf;
  // The most a state of `mask` may cost and still be within the bound, worked out once a mask
  // (when first asked: a mask is asked when a state of a mask one cell smaller reaches it).
  thread_local std::vector<double> limits;
  thread_local std::vector<std::uint8_t> limit_known;
  if (limits.size() < masks) limits.resize(masks);
  limit_known.assign(masks, 0);
  const auto limit_of = [&](std::size_t mask) {
    if (limit_known[mask]) return limits[mask];
    double rest = all_least;  // the least the cells not in mask add
    double home = kInf;       // the least leg home from one of them
    for (std::size_t c = 0; c < n; ++c)
      if (mask & (std::size_t{1} << c))
        rest -= least_added[c];
      else
        home = std::min(home, least_home[c]);
    if (mask == masks - 1) home = 0;  // the legs home are added after the search
    limit_known[mask] = 1;
    return limits[mask] = bound - std::max(0.0, rest + home) * (1 - 1e-9);
  };
  // A state is written only within its mask's limit: one beyond it would never be expanded (nor,
  // in the full mask, be the best: it costs more than the bound), and one that ends within it
  // costs less than any write beyond it, so the states kept have the same costs and parents.
  const auto search = [&]<bool kCrossed>() {
    for (std::size_t mask = 1; mask < masks; ++mask) {
      if (!reached[mask]) continue;
      const double* row = &cost[mask * states];
      const double limit = limit_of(mask);
      // The cells in the mask, then those out of it, each in ascending order (the plain loops').
      for (std::size_t in = mask; in != 0; in &= in - 1) {
        const auto c = std::size_t(std::countr_zero(in));
        for (std::size_t v = 0; v < variants[c]; ++v) {
          const std::size_t s = c * kMaxVariants + v;
          const double here = row[s];
          if (here == kInf || here > limit) continue;
          for (std::size_t out = ~mask & (masks - 1); out != 0; out &= out - 1) {
            const auto c2 = std::size_t(std::countr_zero(out));
            const std::size_t next_mask = mask | (std::size_t{1} << c2);
            const std::uint64_t unflown = ~std::uint64_t{0} & ~next_mask;
            const double next_limit = limit_of(next_mask);
            double* next_row = &cost[next_mask * states];
            for (std::size_t v2 = 0; v2 < variants[c2]; ++v2) {
              const std::size_t s2 = c2 * kMaxVariants + v2, at = s * states + s2;
              double transit = between[at];
              if constexpr (kCrossed)
                transit = penalised(transit, p.crossing_weight, crossed[at] & unflown);
              const double total = here + transit + internal[s2];
              if (total > next_limit) continue;
              reach(next_mask);
              if (total < next_row[s2]) {
                next_row[s2] = total;
                parent[next_mask * states + s2] = static_cast<std::uint8_t>(s);
              }
            }
          }
        }
      }
    }
  };
  if (p.crossed)
    search.template operator()<true>();
  else
    search.template operator()<false>();
  const std::size_t full = (std::size_t{1} << n) - 1;
  reach(full);  // (every tour pruned: none is expected) as a plain search's row, all kInf
  CellOrder best;
  best.objective_m = kInf;
  std::size_t best_state = 0;
  for (std::size_t s = 0; s < states; ++s) {
    if (cost[full * states + s] == kInf) continue;
    const double total = cost[full * states + s] + t.to_home(s / kMaxVariants, s % kMaxVariants);
    if (total < best.objective_m) {
      best.objective_m = total;
      best_state = s;
    }
  }
  for (std::size_t mask = full, s = best_state; mask != 0;) {
    best.visits.push_back({s / kMaxVariants, s % kMaxVariants});
    const std::size_t previous = parent[mask * states + s];
    mask &= ~(std::size_t{1} << (s / kMaxVariants));
    s = previous;
  }
  std::reverse(best.visits.begin(), best.visits.end());
  return finished(p, best);
}

namespace {

// Nearest neighbour: the cheapest next (transit + internal) from where the drone is.
std::vector<std::size_t> nearest_neighbour(const CellOrderProblem& p) {
  const std::size_t n = p.cells.size();
  std::vector<std::size_t> order;
  std::vector<char> used(n, 0);
  // A cell whose least internal length is no less than the best cost so far cannot win (its
  // cost adds a transit of at least 0 to it; ties keep the first), so its transits are not
  // asked: on 10,000-vertex areas with hundreds of cells this ranking ran for every direction.
  std::vector<double> least_internal(n, kInf);
  for (std::size_t c = 0; c < n; ++c)
    for (const CellVariant& v : p.cells[c])
      least_internal[c] = std::min(least_internal[c], v.internal_m);
  geometry::Point2 at = p.home;
  for (std::size_t k = 0; k < n; ++k) {
    double best = kInf;
    std::size_t best_cell = 0, best_variant = 0;
    for (std::size_t c = 0; c < n; ++c) {
      if (used[c] || least_internal[c] >= best) continue;
      for (std::size_t v = 0; v < p.cells[c].size(); ++v) {
        const double cost = p.distance(at, p.cells[c][v].entry) + p.cells[c][v].internal_m;
        if (cost < best) {
          best = cost;
          best_cell = c;
          best_variant = v;
        }
      }
    }
    used[best_cell] = 1;
    order.push_back(best_cell);
    at = p.cells[best_cell][best_variant].exit;
  }
  return order;
}

}  // namespace

namespace {

// nearest_neighbour() when the distance is never below the straight one (straight or routed
// transits), the same order: the brute force asks every cell at every step (O(n² v); on
// 10,000-vertex areas it ranked ~100 directions of ~250 cells, and with routed transits each
// question is a shortest-path search, the far ones the dearest), this one only the cells near
// enough to win. The variants' entries sit in a uniform grid; buckets are taken ring by ring
// around the drone's bucket, and the search stops once a ring's least straight distance plus the
// least internal length still unflown exceeds the best cost; an entry whose straight distance
// plus internal length exceeds it is not asked either (nothing so skipped can reach the best,
// ties included: a cost is a sum of non-negative terms, rounding is monotone, and the margin
// covers a routed length's rounding below the straight one). Ties go to the lower cell, then the
// lower variant, as the brute force's first strict improvement. Empty when it does not apply (a
// cell without variants, a non-finite value, a negative internal length): the caller then asks
// the brute force.
std::vector<std::size_t> nearest_neighbour_grid(const CellOrderProblem& p) {
  const std::size_t n = p.cells.size();
  struct Entry {
    geometry::Point2 at;
    double internal_m;
    std::size_t cell, variant;
  };
  std::vector<Entry> entries;
  double x0 = kInf, y0 = kInf, x1 = -kInf, y1 = -kInf;
  std::vector<double> least_internal(n, kInf);
  const auto finite = [](geometry::Point2 q) { return std::isfinite(q.x) && std::isfinite(q.y); };
  if (!finite(p.home)) return {};
  for (std::size_t c = 0; c < n; ++c) {
    if (p.cells[c].empty()) return {};
    for (std::size_t v = 0; v < p.cells[c].size(); ++v) {
      const CellVariant& cv = p.cells[c][v];
      if (!finite(cv.entry) || !finite(cv.exit) || !std::isfinite(cv.internal_m) ||
          !(cv.internal_m >= 0))
        return {};
      entries.push_back({cv.entry, cv.internal_m, c, v});
      least_internal[c] = std::min(least_internal[c], cv.internal_m);
      x0 = std::min(x0, cv.entry.x);
      y0 = std::min(y0, cv.entry.y);
      x1 = std::max(x1, cv.entry.x);
      y1 = std::max(y1, cv.entry.y);
    }
  }
  // About two entries a bucket, square buckets, at most 1024 a side.
  const double w = x1 - x0, h = y1 - y0;
  const double cell_m = std::max({std::sqrt(w * h * 2 / double(entries.size())),
                                  std::max(w, h) / 1024, 1e-9 * (1 + std::max(w, h))});
  const long columns = std::min(1024L, long(w / cell_m) + 1);
  const long rows = std::min(1024L, long(h / cell_m) + 1);
  const auto column = [&](double x) {
    const double f = (x - x0) / cell_m;
    return f > 0 ? std::min(columns - 1, long(f)) : 0L;
  };
  const auto row = [&](double y) {
    const double f = (y - y0) / cell_m;
    return f > 0 ? std::min(rows - 1, long(f)) : 0L;
  };
  // The buckets in one array (bucket b's entries from start[b] to end[b], in entry order), not a
  // vector each, built and freed for every direction ranked (~1 % of a routed plan's
  // instructions). A cell's entries are consecutive in `entries`, each with its bucket in
  // `in_bucket`.
  const std::size_t buckets = std::size_t(columns * rows);
  std::vector<std::size_t> in_bucket(entries.size()), start(buckets + 1, 0), end(buckets);
  std::vector<std::size_t> first_entry(n + 1, entries.size());
  for (std::size_t k = entries.size(); k-- > 0;) first_entry[entries[k].cell] = k;
  for (std::size_t k = 0; k < entries.size(); ++k) {
    in_bucket[k] = std::size_t(row(entries[k].at.y) * columns + column(entries[k].at.x));
    ++start[in_bucket[k] + 1];
  }
  for (std::size_t b = 0; b < buckets; ++b) start[b + 1] += start[b];
  std::vector<std::size_t> items(entries.size());
  std::copy(start.begin(), start.end() - 1, end.begin());
  for (std::size_t k = 0; k < entries.size(); ++k) items[end[in_bucket[k]]++] = k;
  std::vector<std::size_t> by_internal(n);  // the least internal length still unflown, in order
  for (std::size_t c = 0; c < n; ++c) by_internal[c] = c;
  std::sort(by_internal.begin(), by_internal.end(), [&](std::size_t a, std::size_t b) {
    return std::pair{least_internal[a], a} < std::pair{least_internal[b], b};
  });
  std::size_t least_at = 0;
  std::vector<char> used(n, 0);
  std::vector<std::size_t> order;
  geometry::Point2 at = p.home;
  for (std::size_t k = 0; k < n; ++k) {
    while (used[by_internal[least_at]]) ++least_at;
    const double least = least_internal[by_internal[least_at]];
    double best = kInf;
    std::size_t best_cell = n, best_variant = 0;
    const auto visit = [&](long rr, long cc) {
      if (rr < 0 || rr >= rows || cc < 0 || cc >= columns) return;
      const std::size_t b = std::size_t(rr * columns + cc);
      for (std::size_t i = start[b]; i < end[b]; ++i) {
        const std::size_t e = items[i];
        const Entry& en = entries[e];
        if (used[en.cell] || least_internal[en.cell] > best ||
            geometry::distance(at, en.at) * (1 - 1e-12) + en.internal_m > best)
          continue;
        const double cost = p.distance(at, en.at) + en.internal_m;
        if (cost < best ||
            (cost == best && std::pair{en.cell, en.variant} < std::pair{best_cell, best_variant})) {
          best = cost;
          best_cell = en.cell;
          best_variant = en.variant;
        }
      }
    };
    // The drone's bucket, clamped to the grid: a point outside is no nearer to any bucket than
    // its projection onto the grid's box. A bucket r rings out is at least r - 1 buckets away
    // from it, r - 3 with the rounding of both bucket indices (each off by at most one).
    const long ci = column(at.x), ri = row(at.y);
    for (long r = 0; r <= std::max(columns, rows); ++r) {
      const double ring_m = r > 3 ? double(r - 3) * cell_m * (1 - 1e-9) : 0.0;
      if (ring_m + least > best) break;
      if (r == 0) {
        visit(ri, ci);
        continue;
      }
      for (long cc = ci - r; cc <= ci + r; ++cc) {
        visit(ri - r, cc);
        visit(ri + r, cc);
      }
      for (long rr = ri - r + 1; rr <= ri + r - 1; ++rr) {
        visit(rr, ci - r);
        visit(rr, ci + r);
      }
    }
    if (best_cell == n) return {};  // not expected: every cost is finite
    used[best_cell] = 1;
    order.push_back(best_cell);
    // Its entries leave their buckets: later steps do not walk over them again.
    for (std::size_t x = first_entry[best_cell]; x < entries.size() && entries[x].cell == best_cell;
         ++x) {
      const std::size_t b = in_bucket[x];
      const auto first = items.begin() + std::ptrdiff_t(start[b]);
      end[b] =
          std::size_t(std::remove_if(first, items.begin() + std::ptrdiff_t(end[b]),
                                     [&](std::size_t e) { return entries[e].cell == best_cell; }) -
                      items.begin());
    }
    at = p.cells[best_cell][best_variant].exit;
  }
  return order;
}

}  // namespace

double order_lower_bound(const CellOrderProblem& p) {
  const std::size_t n = p.cells.size();
  if (n == 0) return 0.0;
  constexpr double kNone = std::numeric_limits<double>::infinity();
  // Every cell's entries (or exits) sorted by x, with their cell: the nearest one to a point, of
  // another cell, is found by scanning outwards from the point's x until |dx| alone is no nearer.
  struct End {
    geometry::Point2 at;
    std::size_t cell;
  };
  const auto ends = [&p](bool exits) {
    std::vector<End> e;
    for (std::size_t c = 0; c < p.cells.size(); ++c)
      for (const CellVariant& v : p.cells[c]) e.push_back({exits ? v.exit : v.entry, c});
    std::sort(e.begin(), e.end(), [](const End& a, const End& b) { return a.at.x < b.at.x; });
    return e;
  };
  const auto nearest = [](const std::vector<End>& e, geometry::Point2 q, std::size_t cell) {
    double best = kNone;
    const auto mid = std::lower_bound(e.begin(), e.end(), q.x,
                                      [](const End& a, double x) { return a.at.x < x; });
    for (auto it = mid; it != e.end() && it->at.x - q.x < best; ++it)
      if (it->cell != cell) best = std::min(best, geometry::distance(it->at, q));
    for (auto it = mid; it != e.begin() && q.x - std::prev(it)->at.x < best; --it)
      if (std::prev(it)->cell != cell)
        best = std::min(best, geometry::distance(std::prev(it)->at, q));
    return best;
  };
  const std::vector<End> entries = ends(false), exits = ends(true);
  double in_sum = 0, out_sum = 0, home_back = kNone, home_out = kNone;
  for (std::size_t c = 0; c < n; ++c) {
    double best_in = kNone, best_out = kNone;
    for (const CellVariant& v : p.cells[c]) {
      const double from_home = geometry::distance(p.home, v.entry);
      const double to_home = geometry::distance(v.exit, p.home);
      best_in = std::min(best_in, v.internal_m + std::min(from_home, nearest(exits, v.entry, c)));
      best_out = std::min(best_out, v.internal_m + std::min(to_home, nearest(entries, v.exit, c)));
      home_out = std::min(home_out, from_home);
      home_back = std::min(home_back, to_home);
    }
    in_sum += best_in;
    out_sum += best_out;
  }
  return std::max(in_sum + home_back, out_sum + home_out);
}

CellOrder nearest_neighbour_order(const CellOrderProblem& p) {
  if (p.cells.empty()) return {};
  Transit t(p, false);
  std::vector<std::size_t> order;
  if (p.distance_at_least_straight) order = nearest_neighbour_grid(p);
  if (order.empty()) order = nearest_neighbour(p);
  return finished(p, best_variants(p, t, order));
}

namespace {

// One candidate order from `order` into `c` (its buffer reused: the local search tries ~10^4 a
// plan): move 0 moves the block of `len` cells at i to start at j, move 1 swaps i and j, move 2
// reverses i..j. False when the move does nothing or does not apply. `changed_end`: one past the
// last position the move changes.
bool moved(const std::vector<std::size_t>& order, int move, std::size_t i, std::size_t j,
           std::size_t len, std::vector<std::size_t>& c, std::size_t& changed_end) {
  const std::size_t n = order.size();
  const auto at = [&c](std::size_t k) { return c.begin() + static_cast<std::ptrdiff_t>(k); };
  if (move == 0) {
    if (i + len > n || (j >= i && j <= i + len - 1) || j + len > n) return false;
    c = order;
    // The block taken out and put back in at j of what is left: a rotation of the stretch
    // between.
    if (j < i)
      std::rotate(at(j), at(i), at(i + len));
    else
      std::rotate(at(i), at(i + len), at(j + len));
    changed_end = std::max(i, j) + len;
    return true;
  }
  if (j <= i) return false;
  c = order;
  if (move == 1)
    std::swap(c[i], c[j]);
  else
    std::reverse(at(i), at(j) + 1);
  changed_end = j + 1;
  return true;
}

// Local search over orders (move one cell or a block of two or three, swap two, reverse a run;
// first improvement); variants are re-optimised exactly for each candidate. Moves reach at most
// `reach` positions and at most `budget` candidates are evaluated (the budget is spent in place).
// `current` holds the layers of `order`; a candidate is filled into `trial` from the first
// position it changes, on a copy of the layers before it, and the two swap when it is kept. The
// candidate's cells after the positions a move changes are the current order's: once the first
// of them is filled, the current order's suffix costs tell whether the candidate can win, without
// the layers after it (fill()'s `tail`; the same candidates are kept).
void local_search(const CellOrderProblem& p, Transit& t, std::vector<std::size_t>& order,
                  CellOrder& best, std::size_t reach, std::size_t& budget, VariantTable& current) {
  const std::size_t n = order.size();
  VariantTable trial;
  std::vector<std::size_t> candidate;
  current.suffix(p, t, order);
  // Transits bounded from below without asking the metric (routed paths are the dear part).
  const bool bounded = p.distance_at_least_straight && p.crossing_weight >= 0;
  for (bool improved = true; improved && budget > 0;) {
    improved = false;
    for (std::size_t i = 0; i < n && budget > 0; ++i)
      for (std::size_t j = i >= reach ? i - reach : 0; j < std::min(n, i + reach + 1) && budget > 0;
           ++j)
        for (int kind = 0; kind < 5 && budget > 0; ++kind) {  // block moves of 1-3, swap, reverse
          const int move = kind < 3 ? 0 : kind - 2;
          std::size_t changed_end = n;
          if (i == j || !moved(order, move, i, j, kind < 3 ? std::size_t(kind) + 1 : 1, candidate,
                               changed_end))
            continue;
          --budget;
          trial.keep_layers_of(current, std::min(i, j));
          if (bounded && changed_end < n &&
              trial.cannot_win(p, t, candidate, std::min(i, j), changed_end,
                               best.objective_m - 1e-9, current))
            continue;
          const double tried = trial.fill(p, t, candidate, std::min(i, j), best.objective_m - 1e-9,
                                          &current, changed_end);
          if (tried < best.objective_m - 1e-9) {
            best.objective_m = tried;
            best.visits = trial.visits(candidate);
            order.swap(candidate);
            std::swap(current, trial);
            current.suffix(p, t, order);
            improved = true;
          }
        }
  }
}

}  // namespace

CellOrder heuristic_cell_order(const CellOrderProblem& p) {
  const std::size_t n = p.cells.size();
  if (n == 0) return {};
  Transit t(p);
  std::vector<std::size_t> order;
  if (p.distance_at_least_straight) order = nearest_neighbour_grid(p);
  if (order.empty()) order = nearest_neighbour(p);
  VariantTable current;
  CellOrder best;
  best.objective_m = current.fill(p, t, order, 0);
  best.visits = current.visits(order);
  // Moves reach at most 8 positions on large instances (O(n reach) candidates a pass, each a DP of
  // O(n v²)) and every position below 24 cells; the evaluations are budgeted so large instances
  // stay fast and still get the local improvements that matter.
  const std::size_t reach = n <= 24 ? n : 8;
  std::size_t budget = 200000 / n;
  local_search(p, t, order, best, reach, budget, current);
  // Iterated local search: a local optimum of these moves was up to 9 % above Held-Karp's on 13
  // scattered cells. Kick the best order (a double bridge: three cut points, the middle two
  // pieces exchanged, which no single move undoes), search again, keep what is shorter. The
  // kicks come from a fixed-seed generator (same problem, same order) and share the budget.
  std::mt19937 kicks(static_cast<std::uint32_t>(n));
  for (int kick = 0; kick < 24 && budget > 0 && n >= 8; ++kick) {
    std::size_t cut[3];
    for (std::size_t& c : cut) c = 1 + kicks() % (n - 1);
    std::sort(cut, cut + 3);
    if (cut[0] == cut[1] || cut[1] == cut[2]) continue;
    std::vector<std::size_t> candidate(order.begin(),
                                       order.begin() + static_cast<std::ptrdiff_t>(cut[0]));
    candidate.insert(candidate.end(), order.begin() + static_cast<std::ptrdiff_t>(cut[1]),
                     order.begin() + static_cast<std::ptrdiff_t>(cut[2]));
    candidate.insert(candidate.end(), order.begin() + static_cast<std::ptrdiff_t>(cut[0]),
                     order.begin() + static_cast<std::ptrdiff_t>(cut[1]));
    candidate.insert(candidate.end(), order.begin() + static_cast<std::ptrdiff_t>(cut[2]),
                     order.end());
    VariantTable table;
    CellOrder tried;
    tried.objective_m = table.fill(p, t, candidate, 0);
    tried.visits = table.visits(candidate);
    local_search(p, t, candidate, tried, reach, budget, table);
    if (tried.objective_m < best.objective_m - 1e-9) {
      best = tried;
      order = candidate;
    }
  }
  return finished(p, best);
}

CellOrder order_cells(const CellOrderProblem& p, std::size_t exact_limit) {
  return p.cells.size() <= exact_limit ? exact_cell_order(p) : heuristic_cell_order(p);
}

}  // namespace swath::planning
