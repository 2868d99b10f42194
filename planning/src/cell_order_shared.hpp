#pragma once
// What the cell orderings share (cell_order.cpp: the heuristics; cell_order_exact.cpp: the exact
// search): the memoised transits with their crossing penalty, and the best variants of an order.

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <tuple>
#include <unordered_map>
#include <utility>

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
  /// `use_bounds` false: bounded() is false whatever the problem (the searches ask every transit
  /// they look at; a test's reference for how many the bounds leave unasked).
  explicit Transit(const CellOrderProblem& p, bool memoise = true, bool use_bounds = true)
      : p_(p), memoise_(memoise), use_bounds_(use_bounds) {
    std::size_t offset = 0;
    for (const auto& cell : p.cells) {
      base_.push_back(offset);
      offset += cell.size();
    }
    const std::size_t n = offset;
    // Every transition in a table where that is small; beyond, only the ones asked, hashed: a
    // concave area of 18,000 one-lane runs (a star) asked for ~10^10 entries and ran out of
    // memory, while its search asks for a few per run.
    dense_ = n <= kDenseVariants;
    if (memoise_ && dense_) exit_to_entry_.assign(n * n, -1.0);
    if (memoise_ && dense_ && p.crossed) crossed_.assign(n * n, kUnknown);
    // The legs from and to home are asked when first needed: a routed one is a shortest-path
    // search (~7 % of a traced outline's plan when all 2n were asked up front), and the searches
    // need those of the cells that come first or last only.
    home_to_entry_.assign(n, -1.0);
    exit_to_home_.assign(n, -1.0);
    size_ = n;
    if (memoise_ && dense_ && p.symmetric) find_twins();
    if (bounded()) find_least_ins();
  }
  /// At most the cost of any transit into cell c from another cell's exit, whatever the memo
  /// holds (bounded() only; 0 otherwise): the least straight length into it, less 1e-12 of it
  /// (lower_cost()'s bound of a transit not asked, and at most a known one's length, which its
  /// penalty only adds to), over every variant of every other cell; 0 beyond kLeastInVariants
  /// variants in all (the scan is quadratic) and for a cell without variants.
  double least_into(std::size_t c) const { return least_into_.empty() ? 0.0 : least_into_[c]; }
  /// The least internal length of cell c's variants (infinity: none).
  double least_internal(std::size_t c) const {
    return least_internal_.empty() ? 0.0 : least_internal_[c];
  }
  /// At most the cost of any transit from cell c1's exit into cell c2 plus the internal length of
  /// the variant it enters, whatever the memo holds (bounded() only): the least over their
  /// variants of least_into()'s straight bound plus that internal length, where every pair's
  /// bound is kept (up to kLeastInVariants variants in all, c1 != c2, both with variants); else
  /// least_into(c2) + least_internal(c2). Never below the latter: the way into c2 from the
  /// cell actually before it, not from the nearest of all (cannot_win()'s bound on the rest).
  double least_step(std::size_t c1, std::size_t c2) const {
    return least_step_.empty() ? least_into(c2) + least_internal(c2)
                               : least_step_[c1 * least_into_.size() + c2];
  }
  /// How many variants cell c has.
  std::size_t variants(std::size_t c) const { return p_.cells[c].size(); }
  double from_home(std::size_t c, std::size_t v) {
    const std::size_t i = base_[c] + v;
    double& d = home_to_entry_[i];
    if (d < 0) {
      ++asked_;
      d = p_.distance(p_.home, p_.cells[c][v].entry);
      if (!twins_.empty()) share_home(twins_[i].entry, d);
    }
    return d;
  }
  double to_home(std::size_t c, std::size_t v) {
    const std::size_t i = base_[c] + v;
    double& d = exit_to_home_[i];
    if (d < 0) {
      ++asked_;
      d = p_.distance(p_.cells[c][v].exit, p_.home);
      if (!twins_.empty()) share_home(twins_[i].exit, d);
    }
    return d;
  }
  /// Whether transits may be left unasked where their lower bounds (lower_cost(), low_from_home(),
  /// low_to_home()) already decide: memoised, `distance_at_least_straight` and a crossing weight
  /// >= 0 (lower_cost()'s precondition).
  bool bounded() const {
    return use_bounds_ && memoise_ && p_.distance_at_least_straight && p_.crossing_weight >= 0;
  }
  /// At most from_home(c, v), without asking: the leg where known, else the straight length less
  /// 1e-12 of it (precondition as for lower_cost()).
  double low_from_home(std::size_t c, std::size_t v) const {
    const double d = home_to_entry_[base_[c] + v];
    return d >= 0 ? d : geometry::distance(p_.home, p_.cells[c][v].entry) * (1 - 1e-12);
  }
  double low_to_home(std::size_t c, std::size_t v) const {
    const double d = exit_to_home_[base_[c] + v];
    return d >= 0 ? d : geometry::distance(p_.cells[c][v].exit, p_.home) * (1 - 1e-12);
  }
  /// How many answers of the metric (lengths, crossings) the memo has taken: unchanged, every
  /// bound it gives is as it was.
  std::uint64_t asked() const { return asked_; }
  bool from_home_known(std::size_t c, std::size_t v) const {
    return home_to_entry_[base_[c] + v] >= 0;
  }
  bool to_home_known(std::size_t c, std::size_t v) const {
    return exit_to_home_[base_[c] + v] >= 0;
  }
  double between(std::size_t c1, std::size_t v1, std::size_t c2, std::size_t v2) {
    if (!memoise_) return p_.distance(p_.cells[c1][v1].exit, p_.cells[c2][v2].entry);
    const std::size_t at = (base_[c1] + v1) * size_ + base_[c2] + v2;
    double& d = dense_ ? exit_to_entry_[at] : sparse_.try_emplace(at).first->second.length_m;
    if (d < 0) {
      ++asked_;
      d = p_.distance(p_.cells[c1][v1].exit, p_.cells[c2][v2].entry);
      if (!twins_.empty()) share(exit_to_entry_, base_[c1] + v1, base_[c2] + v2, d);
      if (dense_) known_now(at);
    }
    return d;
  }
  /// The cells whose lanes the transit crosses (0 without problem.crossed).
  std::uint64_t crossed(std::size_t c1, std::size_t v1, std::size_t c2, std::size_t v2) {
    if (!p_.crossed) return 0;
    if (!memoise_) return p_.crossed(p_.cells[c1][v1].exit, p_.cells[c2][v2].entry);
    const std::size_t at = (base_[c1] + v1) * size_ + base_[c2] + v2;
    std::uint64_t& m = dense_ ? crossed_[at] : sparse_.try_emplace(at).first->second.crossed;
    if (m == kUnknown) {
      ++asked_;
      m = p_.crossed(p_.cells[c1][v1].exit, p_.cells[c2][v2].entry) & ~kUnknown;
      if (!twins_.empty()) share(crossed_, base_[c1] + v1, base_[c2] + v2, m);
      if (dense_) known_now(at);
    }
    return m;
  }
  /// At most cost(c1, v1, c2, v2, unflown), without asking the metric: the cost where known, the
  /// length without the penalty where only that is known (the penalty only adds, for
  /// `crossing_weight` >= 0), else the straight length less 1e-12 of it. Precondition:
  /// `distance_at_least_straight` (the margin covers a routed length's rounding below the
  /// straight one) and `crossing_weight` >= 0.
  double lower_cost(std::size_t c1, std::size_t v1, std::size_t c2, std::size_t v2,
                    std::uint64_t unflown) const {
    double low = 0;
    cost_if_known(c1, v1, c2, v2, unflown, low);
    return low;
  }
  /// True with cost(c1, v1, c2, v2, unflown) in `out` where the memo holds its length and (with
  /// problem.crossed) its crossings, else false with lower_cost() in `out`. Precondition: as for
  /// lower_cost().
  bool cost_if_known(std::size_t c1, std::size_t v1, std::size_t c2, std::size_t v2,
                     std::uint64_t unflown, double& out) const {
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
        if (!p_.crossed) {
          out = known.length_m;
          return true;
        }
        if (known.crossed == kUnknown) {
          out = known.length_m;
          return false;
        }
        out = penalised(known.length_m, p_.crossing_weight, known.crossed & unflown);
        return true;
      }
    }
    out = geometry::distance(p_.cells[c1][v1].exit, p_.cells[c2][v2].entry) * (1 - 1e-12);
    return false;
  }
  /// The least of before[u] + lower_cost(c1, u, c2, v2, unflown) + internal_m over u < count,
  /// summed and compared in that order (a layer of VariantTable::cannot_win()).
  /// `came` (optional): the first u giving it (0 where none is below infinity).
  double least_through(const double* before, std::size_t c1, std::size_t count, std::size_t c2,
                       std::size_t v2, std::uint64_t unflown, double internal_m,
                       std::size_t* came = nullptr) const {
    double best = kInf;
    std::size_t first = 0;
    if (!memoise_ || !dense_) {  // lower_cost() asks the memo entry by entry
      for (std::size_t u = 0; u < count; ++u) {
        const double c = before[u] + lower_cost(c1, u, c2, v2, unflown) + internal_m;
        if (c < best) {
          best = c;
          first = u;
        }
      }
      if (came) *came = first;
      return best;
    }
    const bool crossings = bool(p_.crossed);
    std::size_t at = base_[c1] * size_ + base_[c2] + v2;  // (base_[c1] + u) * size_ + ...
    for (std::size_t u = 0; u < count; ++u, at += size_) {
      const double low =
          dense_low(at, p_.cells[c1][u].exit, p_.cells[c2][v2].entry, unflown, crossings);
      const double c = before[u] + low + internal_m;
      if (c < best) {
        best = c;
        first = u;
      }
    }
    if (came) *came = first;
    return best;
  }
  /// lower_cost() of the dense table's entry `at`, the transit from `exit` to `entry` (the same
  /// value, without the look-up of the cells' points).
  double dense_low(std::size_t at, geometry::Point2 exit, geometry::Point2 entry,
                   std::uint64_t unflown, bool crossings) const {
    const double d = exit_to_entry_[at];
    if (d < 0) return geometry::distance(exit, entry) * (1 - 1e-12);
    if (!crossings || crossed_[at] == kUnknown) return d;
    return penalised(d, p_.crossing_weight, crossed_[at] & unflown);
  }
  /// least_through() for every variant v2 of c2 at once, into layer[v2] (internal_m: the
  /// variant's), with the first u giving it in came[v2]: the same sums and comparisons, the
  /// table's rows and the ends' points found once a layer (VariantTable::cannot_win() fills ~10^5
  /// layers a plan).
  void least_layer(const double* before, std::size_t c1, std::size_t count, std::size_t c2,
                   std::uint64_t unflown, double* layer, std::uint8_t* came) const {
    const auto& variants = p_.cells[c2];
    if (!memoise_ || !dense_) {
      for (std::size_t v2 = 0; v2 < variants.size(); ++v2) {
        std::size_t u = 0;
        layer[v2] = least_through(before, c1, count, c2, v2, unflown, variants[v2].internal_m, &u);
        came[v2] = static_cast<std::uint8_t>(u);
      }
      return;
    }
    const bool crossings = bool(p_.crossed);
    // Each variant's least over u of before[u] + low(at, u, v2) + its internal length, with the
    // table's entry `at` of (c1, u) -> (c2, v2).
    const auto fill = [&](const auto& low) {
      for (std::size_t v2 = 0; v2 < variants.size(); ++v2) {
        const double internal_m = variants[v2].internal_m;
        double best = kInf;
        std::size_t first = 0;
        std::size_t at = base_[c1] * size_ + base_[c2] + v2;  // (base_[c1] + u) * size_ + ...
        for (std::size_t u = 0; u < count; ++u, at += size_) {
          const double c = before[u] + low(at, u, v2) + internal_m;
          if (c < best) {
            best = c;
            first = u;
          }
        }
        layer[v2] = best;
        came[v2] = static_cast<std::uint8_t>(first);
      }
    };
    if (!low_length_.empty()) {  // dense_low()'s values from the bounds' tables: the same sums
      const double weight = p_.crossing_weight;
      // Without a crossing still to be flown the penalty is the length times exactly 1 (a finite
      // weight: the tables are kept only then), so the length as it is.
      fill([&](std::size_t at, std::size_t, std::size_t) {
        const std::uint64_t m = crossings ? low_crossed_[at] & unflown : 0;
        return m != 0 ? penalised(low_length_[at], weight, m) : low_length_[at];
      });
      return;
    }
    const CellVariant* from = p_.cells[c1].data();
    fill([&](std::size_t at, std::size_t u, std::size_t v2) {
      return dense_low(at, from[u].exit, variants[v2].entry, unflown, crossings);
    });
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
  bool use_bounds_;
  std::uint64_t asked_ = 0;
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

  /// Up to this many variants in all, least_into() scans every pair (~10^5 distances) and the
  /// bounds' tables are kept.
  static constexpr std::size_t kLeastInVariants = 320;
  std::vector<double> least_into_, least_internal_;  ///< per cell; empty: not bounded()
  std::vector<double> least_step_;                   ///< least_step() per pair of cells
  // The dense table's lower_cost() before its penalty, kept up to date (known_now()): the
  // length where asked, else the straight length less 1e-12 of it (computed once, not per
  // layer: least_layer() reads every entry of a move's layers, ~10^5 layers a plan); and the
  // crossings where both they and the length are known, else none. penalised() of the two is
  // dense_low()'s value bit for bit: with no crossing it is the length times 1 + weight x 0,
  // exactly 1 for a finite weight (else the tables are not kept). Up to kLeastInVariants.
  std::vector<double> low_length_;
  std::vector<std::uint64_t> low_crossed_;
  void find_least_ins() {
    const std::size_t n = p_.cells.size();
    least_internal_.assign(n, kInf);
    for (std::size_t c = 0; c < n; ++c)
      for (const CellVariant& v : p_.cells[c])
        least_internal_[c] = std::min(least_internal_[c], v.internal_m);
    if (size_ > kLeastInVariants || !dense_) return;
    low_length_.assign(size_ * size_, 0);
    least_into_.assign(n, kInf);
    for (std::size_t a = 0; a < n; ++a)
      for (std::size_t u = 0; u < p_.cells[a].size(); ++u)
        for (std::size_t c = 0; c < n; ++c)
          for (std::size_t v = 0; v < p_.cells[c].size(); ++v) {
            const std::size_t at = (base_[a] + u) * size_ + base_[c] + v;
            low_length_[at] =
                geometry::distance(p_.cells[a][u].exit, p_.cells[c][v].entry) * (1 - 1e-12);
            if (c != a) least_into_[c] = std::min(least_into_[c], low_length_[at]);
          }
    for (double& d : least_into_)
      if (d == kInf) d = 0;  // a cell no other cell leads into: nothing to bound
    find_least_steps();
    if (!std::isfinite(p_.crossing_weight)) {
      low_length_.clear();
      return;
    }
    if (p_.crossed) low_crossed_.assign(size_ * size_, 0);
  }
  /// least_step()'s table from low_length_'s straight bounds (before any transit is asked: a
  /// transit's cost is never below them, its penalty only adds for a weight >= 0).
  void find_least_steps() {
    const std::size_t n = p_.cells.size();
    least_step_.assign(n * n, kInf);
    for (std::size_t a = 0; a < n; ++a)
      for (std::size_t c = 0; c < n; ++c) {
        double& least = least_step_[a * n + c];
        for (std::size_t u = 0; u < p_.cells[a].size(); ++u) {
          const double* low = &low_length_[(base_[a] + u) * size_ + base_[c]];
          for (std::size_t v = 0; v < p_.cells[c].size(); ++v)
            least = std::min(least, low[v] + p_.cells[c][v].internal_m);
        }
        // The same cell twice is no step of an order; a cell without variants has no way.
        if (a == c || least == kInf) least = least_into_[c] + least_internal_[c];
      }
  }
  /// The bounds' tables at dense entry `at` after its length or crossings were asked.
  void known_now(std::size_t at) {
    if (low_length_.empty() || exit_to_entry_[at] < 0) return;
    low_length_[at] = exit_to_entry_[at];
    if (p_.crossed && crossed_[at] != kUnknown) low_crossed_[at] = crossed_[at];
  }

  // Twins (problem.symmetric, dense tables): the entries of the tables that are one pair of points
  // either way round. A one-lane run's exit is its other variant's entry, so the transit from one
  // run to another is also a transit from that one back (an n-run candidate has each pair of
  // points in up to 2 x 2 places), and a leg from home to a point is the leg home from it. The
  // metric answers a pair the same whichever entry asks it (CellOrderProblem::symmetric): an
  // answer written into its twins is what asking them would give, so every search reads the same
  // values and decides the same, with one question a pair where there were up to four (and the
  // twins' costs known exactly, not bounded, where the searches look at them).
  struct Ends {
    std::uint32_t entry, exit;  ///< the variant's points, numbered
  };
  std::vector<Ends> twins_;                                        ///< per variant index
  std::vector<std::vector<std::uint32_t>> exits_at_, entries_at_;  ///< per point: variant indices
  void find_twins() {
    std::unordered_map<std::uint64_t, std::vector<std::pair<geometry::Point2, std::uint32_t>>> ids;
    std::uint32_t count = 0;
    const auto id = [&](geometry::Point2 q) {
      // Equal points (as doubles compare: -0 == 0) get one number.
      const double x = q.x == 0 ? 0.0 : q.x, y = q.y == 0 ? 0.0 : q.y;
      auto& bucket = ids[std::bit_cast<std::uint64_t>(x) * 0x9e3779b97f4a7c15ull ^
                         std::bit_cast<std::uint64_t>(y)];
      for (const auto& [at, k] : bucket)
        if (at.x == q.x && at.y == q.y) return k;
      bucket.push_back({q, count});
      return count++;
    };
    twins_.resize(size_);
    for (std::size_t c = 0; c < p_.cells.size(); ++c)
      for (std::size_t v = 0; v < p_.cells[c].size(); ++v)
        twins_[base_[c] + v] = {id(p_.cells[c][v].entry), id(p_.cells[c][v].exit)};
    exits_at_.assign(count, {});
    entries_at_.assign(count, {});
    for (std::size_t i = 0; i < size_; ++i) {
      exits_at_[twins_[i].exit].push_back(std::uint32_t(i));
      entries_at_[twins_[i].entry].push_back(std::uint32_t(i));
    }
  }
  /// `value`, the answer for the transit from variant i's exit to variant j's entry, into every
  /// entry of `table` from a variant leaving at either point to one entered at the other.
  template <class T>
  void share(std::vector<T>& table, std::size_t i, std::size_t j, T value) {
    const std::uint32_t a = twins_[i].exit, b = twins_[j].entry;
    for (const std::uint32_t from : exits_at_[a])
      for (const std::uint32_t to : entries_at_[b]) {
        table[from * size_ + to] = value;
        known_now(from * size_ + to);
      }
    for (const std::uint32_t from : exits_at_[b])
      for (const std::uint32_t to : entries_at_[a]) {
        table[from * size_ + to] = value;
        known_now(from * size_ + to);
      }
  }
  /// `d`, the leg between home and point `at`, into both legs' tables wherever `at` is an end.
  void share_home(std::uint32_t at, double d) {
    for (const std::uint32_t i : entries_at_[at]) home_to_entry_[i] = d;
    for (const std::uint32_t i : exits_at_[at]) exit_to_home_[i] = d;
  }
};

// The least of values[0] to values[count - 1] (infinity for none), kept as a scan in order
// keeping strict improvements finds it (a layer's least variant).
inline double least_of(const double* values, std::size_t count) {
  double least = kInf;
  for (std::size_t i = 0; i < count; ++i) least = std::min(least, values[i]);
  return least;
}

inline std::uint64_t bit(std::size_t cell) {
  return cell < 63 ? std::uint64_t{1} << cell : 0;
}

// The least of value[u] over u < count and the first u giving it, as a scan in order of u keeping
// strict improvements finds them (ties to the lower u; u = 0 where none is below infinity), where
// value[u] is exact for known[u] and otherwise a lower bound that ask(u) replaces by the exact
// value. The bounds are asked in ascending order (ties: lower u first) until the next one cannot
// beat the least exact value so far, ties included (above it, or equal from a later u): a value
// is at least its bound, so one not asked is neither the least nor the first to tie it. The
// same least and u as asking every value, with a routed transit's search only where its straight
// bound cannot decide.
template <class Ask>
std::pair<double, std::size_t> first_least(std::size_t count, double* value, bool* known, Ask ask) {
  const auto least_known = [&] {
    std::pair<double, std::size_t> best{kInf, 0};
    for (std::size_t u = 0; u < count; ++u)
      if (known[u] && value[u] < best.first) best = {value[u], u};
    return best;
  };
  for (std::pair<double, std::size_t> best = least_known();; best = least_known()) {
    std::size_t next = count;  // the least bound not asked yet
    for (std::size_t u = 0; u < count; ++u)
      if (!known[u] && (next == count || value[u] < value[next])) next = u;
    if (next == count || value[next] > best.first ||
        (value[next] == best.first && (best.first == kInf || next > best.second)))
      return best;
    value[next] = ask(next);
    known[next] = true;
  }
}

// Which bounds' layers a block move may keep from the move before it (VariantTable::cannot_win()'s
// `kept_to`): a block moved from i to j > i after the same block moved from i to j - 1, with the
// same current order (`version`) and no transit asked since (`asked`), has the same layers up to
// j - 2 (the same cells there and after each); otherwise none are kept. One per block length.
class KeptLayers {
 public:
  /// The move from i to j, bounded now: the position up to which its layers are the last move's
  /// (0: none), and that move remembered as the last.
  std::size_t next(std::size_t i, std::size_t j, std::uint64_t asked, std::uint64_t version) {
    const bool follows = i_ == i && j_ + 1 == j && asked_ == asked && version_ == version;
    i_ = i;
    j_ = j;
    asked_ = asked;
    version_ = version;
    return follows ? j - 1 : 0;
  }

 private:
  std::size_t i_ = std::size_t(-1), j_ = 0;
  std::uint64_t asked_ = 0, version_ = 0;
};

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
    const bool lazy = t.bounded();
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
          if (lazy) {
            std::tie(best, came) =
                least_through_asked(t, before, b, before_count, cell, v, unflown, internal);
          } else {
            for (std::size_t u = 0; u < before_count; ++u) {
              const double c = before[u] + t.cost(b, u, cell, v, unflown) + internal;
              if (c < best) {
                best = c;
                came = u;
              }
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
    const std::size_t last_cell = order[n - 1], count = p.cells[last_cell].size();
    const double* layer = &cost_[(n - 1) * kMaxVariants];
    if (lazy) {
      double value[kMaxVariants];
      bool known[kMaxVariants];
      for (std::size_t v = 0; v < count; ++v) {
        known[v] = t.to_home_known(last_cell, v);
        value[v] = layer[v] + t.low_to_home(last_cell, v);
      }
      double best_cost = kInf;
      std::tie(best_cost, last_) = first_least(
          count, value, known, [&](std::size_t v) { return layer[v] + t.to_home(last_cell, v); });
      return best_cost;
    }
    last_ = 0;
    double best_cost = kInf;
    for (std::size_t v = 0; v < count; ++v) {
      const double c = layer[v] + t.to_home(last_cell, v);
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
  /// Of `other`'s layers before `from`, the one cannot_win() reads (layer from - 1): all a move
  /// needs until it is filled (keep_layers_of() then), where most are rejected by their bounds.
  void keep_layer_before(const VariantTable& other, std::size_t from) {
    cost_.resize(other.cost_.size());
    if (from == 0) return;
    const auto at = std::ptrdiff_t((from - 1) * kMaxVariants);
    std::copy(other.cost_.begin() + at, other.cost_.begin() + at + std::ptrdiff_t(kMaxVariants),
              cost_.begin() + at);
  }
  /// The cost of the rest of `order` (this table's last filled order, filled whole) after each
  /// layer's variant: transits on (with the penalties of the cells still after them), the later
  /// cells' internal lengths and the leg home. What fill()'s `tail` reads.
  ///
  /// `kept` (optional): a table whose suffix() was of an order with the same cells as `order`
  /// from position `same_from` on (the local search's order before the move it keeps). Its costs
  /// at those positions are this order's, copied: each is a sum over the same cells, with the
  /// same cells after each, and the least of exact costs (first_least()'s value is the exact
  /// least whatever transits are known), so the same value bit for bit.
  void suffix(const CellOrderProblem& p, Transit& t, const std::vector<std::size_t>& order,
              const VariantTable* kept = nullptr, std::size_t same_from = std::size_t(-1)) {
    const std::size_t n = order.size();
    rest_cost_.assign(n * kMaxVariants, kInf);
    after_all_.assign(n + 1, 0);
    for (std::size_t k = n; k-- > 0;) after_all_[k] = after_all_[k + 1] | bit(order[k]);
    if (n == 0) return;
    std::size_t first_kept = n;  // the positions from here on copied from `kept`
    if (kept && same_from < n) {
      first_kept = same_from;
      std::copy(kept->rest_cost_.begin() + std::ptrdiff_t(first_kept * kMaxVariants),
                kept->rest_cost_.begin() + std::ptrdiff_t(n * kMaxVariants),
                rest_cost_.begin() + std::ptrdiff_t(first_kept * kMaxVariants));
    } else {
      for (std::size_t v = 0; v < p.cells[order[n - 1]].size(); ++v)
        rest_cost_[(n - 1) * kMaxVariants + v] = t.to_home(order[n - 1], v);
    }
    const bool lazy = t.bounded();
    for (std::size_t k = std::min(first_kept, n - 1); k-- > 0;) {
      const std::uint64_t after = after_all_[k + 2];  // cells flown after position k + 1
      const auto& next = p.cells[order[k + 1]];
      const double* rest = &rest_cost_[(k + 1) * kMaxVariants];
      for (std::size_t u = 0; u < p.cells[order[k]].size(); ++u) {
        double best = kInf;
        if (lazy) {  // the least only: first_least()'s value, the same whichever v gives it
          double value[kMaxVariants];
          bool known[kMaxVariants];
          for (std::size_t v = 0; v < next.size(); ++v) {
            double d = 0;
            known[v] = t.cost_if_known(order[k], u, order[k + 1], v, after, d);
            value[v] = d + next[v].internal_m + rest[v];
          }
          best =
              first_least(next.size(), value, known, [&](std::size_t v) {
                return t.cost(order[k], u, order[k + 1], v, after) + next[v].internal_m + rest[v];
              }).first;
        } else {
          for (std::size_t v = 0; v < next.size(); ++v)
            best = std::min(
                best, t.cost(order[k], u, order[k + 1], v, after) + next[v].internal_m + rest[v]);
        }
        rest_cost_[k * kMaxVariants + u] = best;
      }
    }
  }
  /// suffix()'s cost of the rest of its order after variant v at position k.
  double rest_cost(std::size_t k, std::size_t v) const { return rest_cost_[k * kMaxVariants + v]; }
  /// Whether `order`, a candidate of the local search whose layers before `from` this table holds
  /// (keep_layers_of(), or keep_layer_before(): only layer from - 1 is read) and whose cells from
  /// `check_at` on are those of the order `tail` last
  /// took the suffix() of, certainly cannot reach below `give_up_m`: its layers `from` to
  /// `check_at` with the transits' lower bounds (Transit::lower_cost()) plus the tail's costs,
  /// less fill()'s margin. Each such layer is at most fill()'s (the same sums of terms no larger,
  /// rounding is monotone), so fill() would give up at `check_at` (or before) too: the same
  /// candidates are kept. Where the bounds cannot reject, the transits on the bounds' cheapest
  /// way through those layers are asked one at a time, the shortest bound first (a short one is
  /// the cheapest search, and asking it tells whether a detour there lifts the way above the
  /// others), the layers refilled from the one it changes, until the bounds reject or that way is
  /// known whole (then no way costs less: fill() decides). A rejected move asks only transits on
  /// ways that looked cheapest, not all that fill()'s layers need. `tail` null: the move changes
  /// the order to its end (check_at its last position), and the legs home (their bounds) stand
  /// for the tail's costs: a rejected move's objective is at least `give_up_m`, which the local
  /// search does not keep either.
  ///
  /// Layers are filled only until one shows the move cannot win (low_layers()), a bound on the
  /// rest ahead of it (`ahead_`) added: most moves are rejected a few layers in.
  ///
  /// `kept_to` (optional, above `from`): this table's layers `from` to `kept_to` - 1 are those of
  /// the last call's (as far as it filled them: `low_end_`), which had the same `from`, the same
  /// layers before it, the same cells at positions up to kept_to - 1 (so the same cells after each:
  /// the rest are the same set) and the same transits known, none asked since (Transit::asked()):
  /// the same sums, not redone. Precondition: t.bounded(); from < check_at < order.size(); kept_to
  /// <= check_at.
  bool cannot_win(const CellOrderProblem& p, Transit& t, const std::vector<std::size_t>& order,
                  std::size_t from, std::size_t check_at, double give_up_m,
                  const VariantTable* tail, std::size_t kept_to = 0) {
    const std::size_t layers = check_at - from + 1;
    const double margin_m = 1e-9 * (1 + std::abs(give_up_m));
    const std::size_t last_cell = order[check_at];
    // ahead_[k - from]: at most what any way costs after layer k: the cheapest rest after layer
    // check_at (the tail's costs, or the legs home), and for each later layer's cell the least
    // transit into it from the cell before it with its internal length (Transit::least_step()).
    ahead_.resize(std::max(ahead_.size(), layers));
    double ahead = kInf;
    for (std::size_t v = 0; v < p.cells[last_cell].size(); ++v)
      ahead = std::min(ahead, tail ? tail->rest_cost_[check_at * kMaxVariants + v]
                                   : t.low_to_home(last_cell, v));
    for (std::size_t k = check_at + 1; k-- > from;) {
      ahead_[k - from] = ahead;
      if (k > from) ahead += t.least_step(order[k - 1], order[k]);
    }
    // The layers the last call filled are kept only as far as it filled them; each kept one
    // may already show that the move cannot win (then none is filled, and the layers kept are
    // those up to it, as where they are filled afresh).
    std::size_t start = std::max(from, std::min(kept_to, low_end_));
    // Before any layer: the least of the layer before `from` (the current order's, exact), the
    // step into the cell at `from` and the rest after it bound every way too (as low_layers()
    // does a layer further on). None counts as filled then (the next move keeps none), as where
    // no layer was kept.
    if (from > 0) {
      const double before =
          least_of(&cost_[(from - 1) * kMaxVariants], p.cells[order[from - 1]].size());
      if (before + t.least_step(order[from - 1], order[from]) + ahead_[0] >= give_up_m + margin_m) {
        low_end_ = from;
        return true;
      }
    }
    // Every entry read below is written first (a layer's variants by low_layers()).
    if (low_.size() < layers * kMaxVariants) low_.resize(layers * kMaxVariants, kInf);
    low_from_.resize(std::max(low_from_.size(), layers * kMaxVariants));
    masks_.resize(layers);
    std::uint64_t after = tail ? tail->after_all_[check_at + 1] : 0;  // the cells after k
    for (std::size_t k = check_at + 1; k-- > from;) {
      masks_[k - from] = after;
      after |= bit(order[k]);
    }
    for (std::size_t k = from; k < start; ++k)
      if (rejects_at(p, order, from, k, give_up_m + margin_m)) {
        low_end_ = k + 1;
        return true;
      }
    for (;;) {
      if (low_layers(p, t, order, from, start, check_at, give_up_m + margin_m)) return true;
      double whole = kInf;
      std::size_t last = 0;  // the last layer's variant on the cheapest way
      for (std::size_t v = 0; v < p.cells[last_cell].size(); ++v) {
        const double w =
            low_[(check_at - from) * kMaxVariants + v] +
            (tail ? tail->rest_cost_[check_at * kMaxVariants + v] : t.low_to_home(last_cell, v));
        if (w < whole) {
          whole = w;
          last = v;
        }
      }
      if (whole - margin_m >= give_up_m) return true;
      if (!ask_on_way(t, order, from, check_at, last, !tail, start)) return false;
    }
  }
  /// One past the last layer the last cannot_win() filled (its check_at + 1 unless a layer
  /// before showed that the move cannot win).
  std::size_t low_end() const { return low_end_; }
  /// cannot_win()'s layers `start` to `check_at` (those before kept) on the transits' lower
  /// bounds, with the variant each came from (`low_from_`: the first of equal ones). True, the
  /// layers after it left unfilled, once a layer k before `check_at` shows the move cannot win:
  /// its least plus ahead_[k - from] at least `reject_m` (cannot_win()'s give_up_m plus its
  /// margin). Sound: any way through the candidate costs its layer-k cost (at least that layer's
  /// least), then for each later cell the transit into it from the cell before it and its
  /// internal length (together at least least_step()), then the rest after
  /// check_at (at least the least of the tail's costs, or of the legs home); every term at least
  /// its bound, so the whole at least their sum, which the margin covers for rounding as for
  /// the whole check (sums of ~10^3 terms, another order of addition). So the move would be
  /// rejected at check_at too, or by fill(): the same moves kept, with the layers after k (the
  /// dear part of a move rejected out of hand) not computed.
  bool low_layers(const CellOrderProblem& p, const Transit& t,
                  const std::vector<std::size_t>& order, std::size_t from, std::size_t start,
                  std::size_t check_at, double reject_m) {
    for (std::size_t k = start; k <= check_at; ++k) {
      const std::size_t c = order[k];
      const auto& variants = p.cells[c];
      double* layer = &low_[(k - from) * kMaxVariants];
      if (k == 0) {
        for (std::size_t v = 0; v < variants.size(); ++v)
          layer[v] = t.low_from_home(c, v) + variants[v].internal_m;
      } else {
        const std::size_t b = order[k - 1], before_count = p.cells[b].size();
        const double* before = k == from ? &cost_[(k - 1) * kMaxVariants] : layer - kMaxVariants;
        const std::uint64_t unflown = masks_[k - from];
        t.least_layer(before, b, before_count, c, unflown, layer,
                      &low_from_[(k - from) * kMaxVariants]);
      }
      low_end_ = k + 1;
      if (k < check_at && rejects_at(p, order, from, k, reject_m)) return true;
    }
    return false;
  }
  /// Whether layer k (before cannot_win()'s check_at) shows the move cannot win: its least plus
  /// ahead_[k - from] at least `reject_m` (low_layers()).
  bool rejects_at(const CellOrderProblem& p, const std::vector<std::size_t>& order,
                  std::size_t from, std::size_t k, double reject_m) const {
    return least_of(&low_[(k - from) * kMaxVariants], p.cells[order[k]].size()) +
               ahead_[k - from] >=
           reject_m;
  }
  /// Asks the transit (or leg from home, or with `home` the leg home after it) with the shortest
  /// bound (the latest of equal ones) among those not known yet on the way low_layers() leads to
  /// variant `last` of layer `check_at`, and sets `start` to the first layer that changes
  /// (check_at + 1: none); false where the whole way is known.
  bool ask_on_way(Transit& t, const std::vector<std::size_t>& order, std::size_t from,
                  std::size_t check_at, std::size_t last, bool home, std::size_t& start) {
    double shortest = kInf;
    bool found = false;
    std::size_t at_k = 0, at_u = 0, at_v = 0;
    if (home && !t.to_home_known(order[check_at], last)) {
      shortest = t.low_to_home(order[check_at], last);
      found = true;
      at_k = check_at + 1;
      at_v = last;
    }
    for (std::size_t k = check_at + 1, v = last; k-- > from;) {
      if (k == 0) {
        if (!t.from_home_known(order[0], v) &&
            (!found || t.low_from_home(order[0], v) < shortest)) {
          found = true;
          at_k = 0;
          at_v = v;
        }
        break;
      }
      const std::size_t u = low_from_[(k - from) * kMaxVariants + v];
      // The layers low_layers() filled for this order (local_search keeps a move's layers only
      // while they are those): a variant of the cell before, not one left from another order.
      assert(u < t.variants(order[k - 1]));
      double low = 0;
      if (!t.cost_if_known(order[k - 1], u, order[k], v, masks_[k - from], low) &&
          (!found || low < shortest)) {
        shortest = low;
        found = true;
        at_k = k;
        at_u = u;
        at_v = v;
      }
      v = u;
    }
    if (!found) return false;
    if (at_k == 0)
      t.from_home(order[0], at_v);
    else if (at_k > check_at)
      t.to_home(order[check_at], at_v);
    else
      t.cost(order[at_k - 1], at_u, order[at_k], at_v, masks_[at_k - from]);
    start = at_k;
    return true;
  }
  /// The least of before[u] + t.cost(b, u, cell, v, unflown) + internal over u < count and the
  /// first u giving it (fill()'s scan), asking only the transits whose bounds cannot decide
  /// (first_least()). Precondition: t.bounded().
  static std::pair<double, std::size_t> least_through_asked(Transit& t, const double* before,
                                                            std::size_t b, std::size_t count,
                                                            std::size_t cell, std::size_t v,
                                                            std::uint64_t unflown,
                                                            double internal) {
    double value[kMaxVariants];
    bool known[kMaxVariants];
    for (std::size_t u = 0; u < count; ++u) {
      double d = 0;
      known[u] = t.cost_if_known(b, u, cell, v, unflown, d);
      value[u] = before[u] + d + internal;
    }
    return first_least(count, value, known, [&](std::size_t u) {
      return before[u] + t.cost(b, u, cell, v, unflown) + internal;
    });
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
  std::vector<std::uint8_t> low_from_;    ///< cannot_win(): the variant each came from
  std::vector<std::uint64_t> masks_;      ///< cannot_win(): the cells after each of its layers
  std::vector<double> ahead_;             ///< cannot_win(): at most the cost after each layer
  std::size_t low_end_ = 0;               ///< one past the last layer low_layers() filled
  std::size_t last_ = 0;
};

/// heuristic_cell_order() with its transits in `t` (Transit(p, true, false): every transit the
/// search looks at asked, the same order).
CellOrder heuristic_cell_order(const CellOrderProblem& p, Transit& t);

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
