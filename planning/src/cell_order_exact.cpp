// The exact cell order (exact_cell_order): Held-Karp over cells and variants, pruned by the bound
// of a good tour.
#include "swath/planning/cell_order.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <unordered_map>

#include "cell_order_shared.hpp"

namespace swath::planning {
namespace {

using cell_order_detail::bit;
using cell_order_detail::finished;
using cell_order_detail::kInf;
using cell_order_detail::penalised;

}  // namespace

namespace {

constexpr std::size_t kMaxVariants = 4;
using Layers = std::array<std::array<double, kMaxVariants>, 16>;

// The search's tables by mask, the thread's, kept between calls (region division orders ~50,000
// shares a plan).
struct MaskTables {
  std::vector<double> cost;
  std::vector<std::uint8_t> parent;
  std::vector<std::uint8_t> reached;
  std::vector<double> limits;
  std::vector<std::uint8_t> limit_known;
};

MaskTables& thread_tables() {
  thread_local MaskTables tables;
  return tables;
}

// Held-Karp over (cell, variant) states, in named steps: the transitions tabulated, the search
// started from home, the least costs for the bound, a good tour's bound, the pruned search, and
// the best tour read back through the parents.
class ExactSearch {
 public:
  explicit ExactSearch(const CellOrderProblem& p)
      : p_(p),
        n_(p.cells.size()),
        states_(n_ * kMaxVariants),
        masks_(std::size_t{1} << n_),
        m_(thread_tables()),
        lazy_(p.distance_at_least_straight && p.crossing_weight >= 0) {}

  CellOrder run() {
    tabulate_transitions();
    start_from_home();
    least_costs();
    bound_ = p_.crossing_weight >= 0 ? improved(greedy_tour()) * (1 + 1e-9) + 1e-9 : kInf;
    if (m_.limits.size() < masks_) m_.limits.resize(masks_);
    m_.limit_known.assign(masks_, 0);
    seed_from_home();
    if (p_.crossed)
      search<true>();
    else
      search<false>();
    return best_tour();
  }

 private:
  // Every transition's length and crossed cells in flat tables: the search below then reads
  // arrays only. Region division orders a share's runs for every share it weighs; with vectors
  // per subset and the memo's checks per transition, 12 runs took ~70 % of a four-drone
  // division's minutes. A routed transit is far dearer than the search (a shortest path round
  // the area's corners: ~100 us, ~45 % of a traced outline's plan when every one was asked), so
  // where the metric is never below the straight distance (`lazy_`) a transition is asked only
  // when first needed: each step below first compares its straight lower bound (less 1e-12 of
  // it, for rounding) with what it must beat, and asks only where that cannot already decide.
  // Every comparison so decided comes out as it would with the transit (the sums are monotone in
  // it, and the crossing penalty only adds for a weight >= 0), so the search keeps the same
  // states, costs and parents; the lower bounds only loosen the limits (least_costs()), which
  // changes which states are visited, never the tour (see there). Unknown entries are NaN.
  void tabulate_transitions() {
    const double unknown = lazy_ ? std::numeric_limits<double>::quiet_NaN() : 0.0;
    between_.assign(states_ * states_, kInf);
    low_.assign(states_ * states_, kInf);
    crossed_.assign(p_.crossed ? states_ * states_ : 0, 0);
    home_in_.assign(states_, unknown);
    home_out_.assign(states_, unknown);
    low_in_.assign(states_, kInf);
    low_out_.assign(states_, kInf);
    for (std::size_t c = 0; c < n_; ++c)
      for (std::size_t v = 0; v < p_.cells[c].size(); ++v) {
        const std::size_t s = c * kMaxVariants + v;
        if (lazy_) {
          low_in_[s] = straight_low(p_.home, p_.cells[c][v].entry);
          low_out_[s] = straight_low(p_.cells[c][v].exit, p_.home);
        } else {
          home_in_[s] = p_.distance(p_.home, p_.cells[c][v].entry);
          home_out_[s] = p_.distance(p_.cells[c][v].exit, p_.home);
        }
        for (std::size_t c2 = 0; c2 < n_; ++c2) {
          if (c2 == c) continue;
          for (std::size_t v2 = 0; v2 < p_.cells[c2].size(); ++v2) {
            const std::size_t at = s * states_ + c2 * kMaxVariants + v2;
            between_[at] = unknown;
            if (lazy_)
              low_[at] = straight_low(p_.cells[c][v].exit, p_.cells[c2][v2].entry);
            else
              ask(at);
          }
        }
      }
  }

  // At most the metric's distance from a to b (`lazy_`: never below the straight one, up to
  // rounding; Transit::lower_cost()'s margin).
  static double straight_low(geometry::Point2 a, geometry::Point2 b) {
    return geometry::distance(a, b) * (1 - 1e-12);
  }
  static bool unknown(double d) { return std::isnan(d); }
  // Transition `at` (state s = at / states_ to state s2 = at % states_) asked of the problem.
  void ask(std::size_t at) {
    const std::size_t s = at / states_, s2 = at % states_;
    const geometry::Point2 exit = p_.cells[s / kMaxVariants][s % kMaxVariants].exit;
    const geometry::Point2 entry = p_.cells[s2 / kMaxVariants][s2 % kMaxVariants].entry;
    between_[at] = p_.distance(exit, entry);
    if (p_.crossed) crossed_[at] = p_.crossed(exit, entry);
  }
  double between(std::size_t at) {
    if (unknown(between_[at])) ask(at);
    return between_[at];
  }
  double from_home(std::size_t s) {
    if (unknown(home_in_[s]))
      home_in_[s] = p_.distance(p_.home, p_.cells[s / kMaxVariants][s % kMaxVariants].entry);
    return home_in_[s];
  }
  double to_home(std::size_t s) {
    if (unknown(home_out_[s]))
      home_out_[s] = p_.distance(p_.cells[s / kMaxVariants][s % kMaxVariants].exit, p_.home);
    return home_out_[s];
  }
  // The transit's length where known, else its lower bound.
  double known_or_low(std::size_t at) const {
    return unknown(between_[at]) ? low_[at] : between_[at];
  }

  // cost[mask * states + cell * 4 + variant]: shortest start from home visiting `mask`, ending in
  // that state; parent: the state before (states: none). The same order of updates as a plain
  // loop over every state of every mask (states outside the mask are never reached), so ties
  // keep the same parents. A mask's row is laid (kInf, no parent) only when a state of it is
  // first written (`reached`), and masks never reached are skipped: with the bound below most
  // are, and filling every row (1.5 MB at 12 cells) and scanning it took more than the search of
  // the reached ones. The tables are the thread's, kept between calls (region division orders
  // ~50,000 shares a plan).
  void reach(std::size_t mask) {
    if (m_.reached[mask]) return;
    m_.reached[mask] = 1;
    std::fill_n(m_.cost.begin() + std::ptrdiff_t(mask * states_), states_, kInf);
    std::fill_n(m_.parent.begin() + std::ptrdiff_t(mask * states_), states_,
                static_cast<std::uint8_t>(states_));
  }

  void start_from_home() {
    if (m_.cost.size() < masks_ * states_) {
      m_.cost.resize(masks_ * states_);
      m_.parent.resize(masks_ * states_);
    }
    m_.reached.assign(masks_, 0);
    internal_.assign(states_, 0.0);
    variants_.resize(n_);
    for (std::size_t c = 0; c < n_; ++c) {
      variants_[c] = p_.cells[c].size();
      for (std::size_t v = 0; v < variants_[c]; ++v)
        internal_[c * kMaxVariants + v] = p_.cells[c][v].internal_m;
    }
  }

  // The states of one cell: from home. Where the leg is not known yet and its lower bound puts the
  // state beyond its mask's limit, it is left at kInf: such a state is never expanded (search()),
  // and with two cells or more never read again.
  void seed_from_home() {
    for (std::size_t c = 0; c < n_; ++c) {
      const std::size_t mask = std::size_t{1} << c;
      reach(mask);
      for (std::size_t v = 0; v < p_.cells[c].size(); ++v) {
        const std::size_t s = c * kMaxVariants + v;
        if (n_ > 1 && unknown(home_in_[s]) && low_in_[s] + internal_[s] > limit_of(mask)) continue;
        m_.cost[mask * states_ + s] = from_home(s) + internal_[s];
      }
    }
  }

  // A bound to prune by: the objective of a good tour (improved(greedy_tour()) below, in the
  // search's own arithmetic), with a margin above its rounding. A state whose cost plus a lower
  // bound on the rest of every tour through it exceeds it is on no optimal tour, nor on a tie of
  // one, and the states an optimal tour passes through, and those that tie them, keep their costs
  // and parents (their predecessors are on an optimal tour too, or give strictly more): the same
  // tour, bit for bit, the search cut to the tours that one does not beat. The rest of a tour
  // enters each cell still to fly once, adding at least its least internal length and its least
  // way in (from home or another cell's exit; a crossing penalty only adds, for a weight >= 0),
  // and comes home once from one of them (`least_home`); where a transit is not asked yet
  // (`lazy_`), its straight lower bound stands for it.
  void least_costs() {
    least_added_.assign(n_, kInf);
    least_home_.assign(n_, kInf);
    for (std::size_t c = 0; c < n_; ++c) {
      double way_in = kInf;
      for (std::size_t v = 0; v < variants_[c]; ++v) {
        const std::size_t s2 = c * kMaxVariants + v;
        least_added_[c] = std::min(least_added_[c], internal_[s2]);
        least_home_[c] =
            std::min(least_home_[c], unknown(home_out_[s2]) ? low_out_[s2] : home_out_[s2]);
        way_in = std::min(way_in, unknown(home_in_[s2]) ? low_in_[s2] : home_in_[s2]);
        for (std::size_t s = 0; s < states_; ++s)
          way_in = std::min(way_in, known_or_low(s * states_ + s2));
      }
      least_added_[c] += std::max(0.0, way_in);
      all_least_ += least_added_[c];
    }
  }

  // Nearest first from home: the cheapest next state (transit with its penalty, and internal; ties
  // to the lower state). Transits not asked yet stand in by their lower bounds, asked cheapest
  // bound first until none can win (first_least(): the same state as asking all).
  std::vector<std::size_t> greedy_tour() {
    std::vector<std::size_t> tour;
    std::size_t at = states_, flown = 0;  // states: at home
    std::array<double, 16 * kMaxVariants> value;
    std::array<bool, 16 * kMaxVariants> known;
    for (std::size_t k = 0; k < n_; ++k) {
      const std::uint64_t unflown_before = ~std::uint64_t{0} & ~flown;
      const auto cost = [&](std::size_t s2) {
        const std::size_t c2 = s2 / kMaxVariants;
        if (at == states_) return from_home(s2) + internal_[s2];
        const std::size_t i = at * states_ + s2;
        double transit = between(i);
        if (p_.crossed)
          transit = penalised(transit, p_.crossing_weight,
                              crossed_[i] & unflown_before & ~(std::uint64_t{1} << c2));
        return transit + internal_[s2];
      };
      for (std::size_t s2 = 0; s2 < states_; ++s2) {
        const std::size_t c2 = s2 / kMaxVariants;
        known[s2] = true;
        value[s2] = kInf;  // not a candidate: never the least
        if ((flown & (std::size_t{1} << c2)) || s2 % kMaxVariants >= variants_[c2]) continue;
        const bool asked =
            at == states_ ? !unknown(home_in_[s2]) : !unknown(between_[at * states_ + s2]);
        if (asked) {
          value[s2] = cost(s2);
        } else {
          known[s2] = false;
          value[s2] = (at == states_ ? low_in_[s2] : low_[at * states_ + s2]) + internal_[s2];
        }
      }
      const auto [best, best_s] =
          cell_order_detail::first_least(states_, value.data(), known.data(), cost);
      if (!(best < kInf)) return std::vector<std::size_t>{};  // a cell without variants
      tour.push_back(best_s);
      at = best_s;
      flown |= std::size_t{1} << (best_s / kMaxVariants);
    }
    return tour;
  }

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
  //
  // kLow: the same sums with each transit not known yet replaced by its lower bound (and the
  // crossing penalty left out), asking nothing: every layer, and so the objective, at most the
  // real fill's, which gives up wherever this one does (or before).
  template <bool kLow = false>
  double fill(const std::array<std::size_t, 16>& order, std::size_t from, Layers& layer,
              double give_up) {
    double rest = 0;  // the least internal lengths of the cells after position k
    for (std::size_t k = from + 1; k < n_; ++k) rest += least_internal_[order[k]];
    std::uint64_t flown = 0;  // the cells up to position k
    for (std::size_t k = 0; k < from; ++k) flown |= std::uint64_t{1} << order[k];
    for (std::size_t k = from; k < n_; ++k) {
      const std::size_t c = order[k];
      flown |= std::uint64_t{1} << c;
      double least = kInf;
      for (std::size_t v = 0; v < variants_[c]; ++v) {
        const std::size_t s2 = c * kMaxVariants + v;
        double best = kInf;
        if (k == 0) {
          best = (kLow && unknown(home_in_[s2]) ? low_in_[s2] : from_home(s2)) + internal_[s2];
        } else {
          best = through<kLow>(order[k - 1], s2, flown, layer[k - 1]);
        }
        layer[k][v] = best;
        least = std::min(least, best);
      }
      if (k + 1 < n_) {
        rest -= least_internal_[order[k + 1]];
        if (least + std::max(0.0, rest) >= give_up) return kInf;
      }
    }
    // The leg home: kLow, its bound where not asked yet; else asked cheapest bound first.
    const std::size_t last = order[n_ - 1];
    double value[kMaxVariants];
    bool known[kMaxVariants];
    for (std::size_t v = 0; v < variants_[last]; ++v) {
      const std::size_t s = last * kMaxVariants + v;
      known[v] = kLow || !unknown(home_out_[s]);
      value[v] = layer[n_ - 1][v] + (unknown(home_out_[s]) ? low_out_[s] : home_out_[s]);
    }
    return cell_order_detail::first_least(
               variants_[last], value, known,
               [&](std::size_t v) { return layer[n_ - 1][v] + to_home(last * kMaxVariants + v); })
        .first;
  }

  // The least of before[u] + transit + internal over the variants u of cell b, the transit from
  // (b, u) to state s2 with its penalty for the cells not in `flown`; kLow: transits not asked yet
  // by their lower bounds (asking none), else asked cheapest bound first until none can win
  // (first_least(): the least a scan asking every one finds).
  template <bool kLow>
  double through(std::size_t b, std::size_t s2, std::uint64_t flown,
                 const std::array<double, kMaxVariants>& before) {
    double value[kMaxVariants];
    bool known[kMaxVariants];
    const auto exact = [&](std::size_t u) {
      const std::size_t at = (b * kMaxVariants + u) * states_ + s2;
      double transit = between(at);
      if (p_.crossed) transit = penalised(transit, p_.crossing_weight, crossed_[at] & ~flown);
      return before[u] + transit + internal_[s2];
    };
    for (std::size_t u = 0; u < variants_[b]; ++u) {
      const std::size_t at = (b * kMaxVariants + u) * states_ + s2;
      known[u] = !unknown(between_[at]);
      value[u] = known[u] ? exact(u) : before[u] + low_[at] + internal_[s2];
    }
    if constexpr (kLow) {
      return cell_order_detail::least_of(value, variants_[b]);
    } else {
      return cell_order_detail::first_least(variants_[b], value, known, exact).first;
    }
  }

  double improved(const std::vector<std::size_t>& tour) {
    for (std::size_t c = 0; c < n_; ++c) {
      least_internal_[c] = kInf;
      for (std::size_t v = 0; v < variants_[c]; ++v)
        least_internal_[c] = std::min(least_internal_[c], internal_[c * kMaxVariants + v]);
    }
    if (tour.empty()) return kInf;
    std::array<std::size_t, 16> order{}, candidate{};
    for (std::size_t k = 0; k < n_; ++k) order[k] = tour[k] / kMaxVariants;
    Layers current, trial;
    double objective = fill(order, 0, current, kInf);
    const auto at = [&candidate](std::size_t k) {
      return candidate.begin() + static_cast<std::ptrdiff_t>(k);
    };
    const auto consider = [&](std::size_t from) {
      std::copy_n(current.begin(), from, trial.begin());
      // A move its transits' lower bounds already rule out asks for none of them.
      if (lazy_ &&
          !(fill<true>(candidate, from, trial, objective * (1 - 1e-12)) < objective * (1 - 1e-12)))
        return false;
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
      for (std::size_t len = 1; len <= 2 && len < n_; ++len)
        for (std::size_t i = 0; i + len <= n_; ++i)
          for (std::size_t j = 0; j + len <= n_; ++j) {
            if (j == i) continue;
            candidate = order;
            if (j < i)
              std::rotate(at(j), at(i), at(i + len));
            else
              std::rotate(at(i), at(i + len), at(j + len));
            better |= consider(std::min(i, j));
          }
      for (std::size_t i = 0; i < n_; ++i)
        for (std::size_t j = i + 2; j < n_; ++j) {
          candidate = order;
          std::reverse(at(i), at(j + 1));
          better |= consider(i);
        }
    }
    return objective;
  }

  // The most a state of `mask` may cost and still be within the bound, worked out once a mask
  // (when first asked: a mask is asked when a state of a mask one cell smaller reaches it).
  double limit_of(std::size_t mask) {
    if (m_.limit_known[mask]) return m_.limits[mask];
    double rest = all_least_;  // the least the cells not in mask add
    double home = kInf;        // the least leg home from one of them
    for (std::size_t c = 0; c < n_; ++c)
      if (mask & (std::size_t{1} << c))
        rest -= least_added_[c];
      else
        home = std::min(home, least_home_[c]);
    if (mask == masks_ - 1) home = 0;  // the legs home are added after the search
    m_.limit_known[mask] = 1;
    return m_.limits[mask] = bound_ - std::max(0.0, rest + home) * (1 - 1e-9);
  }

  // A state is written only within its mask's limit: one beyond it would never be expanded (nor,
  // in the full mask, be the best: it costs more than the bound), and one that ends within it
  // costs less than any write beyond it, so the states kept have the same costs and parents.
  template <bool kCrossed>
  void search() {
    Sources from;
    for (std::size_t mask = 1; mask < masks_; ++mask) {
      if (!m_.reached[mask]) continue;
      const double limit = limit_of(mask);
      // The mask's states to expand, cells then variants ascending (the plain loops' order).
      from.count = 0;
      for (std::size_t in = mask; in != 0; in &= in - 1) {
        const auto c = std::size_t(std::countr_zero(in));
        for (std::size_t v = 0; v < variants_[c]; ++v) {
          const std::size_t s = c * kMaxVariants + v;
          const double here = m_.cost[mask * states_ + s];
          if (here == kInf || here > limit) continue;
          from.state[from.count] = static_cast<std::uint8_t>(s);
          from.here[from.count++] = here;
        }
      }
      if (from.count > 0) expand<kCrossed>(mask, from);
    }
  }

  // The states of a mask that are expanded, with their costs.
  struct Sources {
    std::array<std::uint8_t, 16 * kMaxVariants> state;
    std::array<double, 16 * kMaxVariants> here;
    std::size_t count = 0;
  };

  // The states one cell beyond `mask`, each written (where within its mask's limit) from the
  // first source giving its least total: what expanding every source in turn writes (only a
  // strictly smaller total replaces one, and a state of the next mask is reached from this mask
  // alone). A total beyond the limit counts as infinite (never written); transits not asked yet
  // stand in by their lower bounds, asked cheapest first until none can win (first_least(): the
  // same least and source as asking all), and not at all where the bound is beyond the limit.
  template <bool kCrossed>
  void expand(std::size_t mask, const Sources& from) {
    std::array<double, 16 * kMaxVariants> value;
    std::array<bool, 16 * kMaxVariants> known;
    for (std::size_t out = ~mask & (masks_ - 1); out != 0; out &= out - 1) {
      const auto c2 = std::size_t(std::countr_zero(out));
      const std::size_t next_mask = mask | (std::size_t{1} << c2);
      const std::uint64_t unflown = ~std::uint64_t{0} & ~next_mask;
      const double next_limit = limit_of(next_mask);
      double* next_row = &m_.cost[next_mask * states_];
      for (std::size_t v2 = 0; v2 < variants_[c2]; ++v2) {
        const std::size_t s2 = c2 * kMaxVariants + v2;
        const auto total = [&](std::size_t i) {
          const std::size_t at = from.state[i] * states_ + s2;
          double transit = between(at);
          if constexpr (kCrossed)
            transit = penalised(transit, p_.crossing_weight, crossed_[at] & unflown);
          const double t = from.here[i] + transit + internal_[s2];
          return t > next_limit ? kInf : t;
        };
        for (std::size_t i = 0; i < from.count; ++i) {
          const std::size_t at = from.state[i] * states_ + s2;
          known[i] = !unknown(between_[at]);
          if (known[i]) {
            value[i] = total(i);
          } else {
            value[i] = from.here[i] + low_[at] + internal_[s2];
            if (value[i] > next_limit) {  // its total too: never written
              value[i] = kInf;
              known[i] = true;
            }
          }
        }
        const auto [least, first] =
            cell_order_detail::first_least(from.count, value.data(), known.data(), total);
        if (!(least < kInf)) continue;
        reach(next_mask);
        if (least < next_row[s2]) {
          next_row[s2] = least;
          m_.parent[next_mask * states_ + s2] = from.state[first];
        }
      }
    }
  }

  // The full mask's cheapest state with its leg home, and the tour back through the parents.
  CellOrder best_tour() {
    const std::size_t full = (std::size_t{1} << n_) - 1;
    reach(full);  // (every tour pruned: none is expected) as a plain search's row, all kInf
    CellOrder best;
    best.objective_m = kInf;
    std::size_t best_state = 0;
    for (std::size_t s = 0; s < states_; ++s) {
      if (m_.cost[full * states_ + s] == kInf) continue;
      if (unknown(home_out_[s]) && m_.cost[full * states_ + s] + low_out_[s] >= best.objective_m)
        continue;
      const double total = m_.cost[full * states_ + s] + to_home(s);
      if (total < best.objective_m) {
        best.objective_m = total;
        best_state = s;
      }
    }
    for (std::size_t mask = full, s = best_state; mask != 0;) {
      best.visits.push_back({s / kMaxVariants, s % kMaxVariants});
      const std::size_t previous = m_.parent[mask * states_ + s];
      mask &= ~(std::size_t{1} << (s / kMaxVariants));
      s = previous;
    }
    std::reverse(best.visits.begin(), best.visits.end());
    return finished(p_, best);
  }

  const CellOrderProblem& p_;
  const std::size_t n_, states_, masks_;
  MaskTables& m_;
  const bool lazy_;  ///< transitions asked when first needed (see tabulate_transitions())
  std::vector<double> between_, low_;       ///< per transition: length (NaN unknown), bound
  std::vector<double> home_in_, home_out_;  ///< per state: legs from and to home (NaN unknown)
  std::vector<double> low_in_, low_out_;    ///< per state: their lower bounds
  std::vector<std::uint64_t> crossed_;
  std::vector<double> internal_;
  std::vector<std::size_t> variants_;
  std::vector<double> least_added_, least_home_;
  double all_least_ = 0;
  double least_internal_[16] = {};
  double bound_ = kInf;
};

}  // namespace

CellOrder exact_cell_order(const CellOrderProblem& p) {
  if (p.cells.size() > 16) throw std::invalid_argument("exact_cell_order: more than 16 cells");
  if (p.cells.empty()) return {};
  return ExactSearch(p).run();
}

}  // namespace swath::planning
