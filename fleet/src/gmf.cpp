// GMF: graph-matching forecasts (paper 000 §3.2.2; docs/swath-fleet.md). For each of the newest
// running task nodes f, the past task nodes whose backward neighbourhoods look like f's
// (Weisfeiler–Lehman signatures, deepened while enough candidates remain) are ranked by how well
// one rigid motion of the plane carries their located neighbours onto f's; what the best ten's
// waiters spawned next is carried over the same motion and clustered into forecast requests.

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>
#include <unordered_map>

#include "dtg_index.hpp"
#include "swath/fleet/forecaster.hpp"
#include "swath/vehicle/random.hpp"

namespace swath::fleet {

namespace {

using detail::at;
using detail::DtgIndex;
using vehicle::Vec3;

// One 64-bit step of an order-dependent hash (SplitMix64's finaliser over the pair).
std::uint64_t mix(std::uint64_t h, std::uint64_t v) {
  std::uint64_t z = h ^ (v + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2));
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

/// sig[k][n] for k = 0..depth: sig₀ = the node's kind (sync nodes: "sync" + the waiter's kind),
/// sig_k = hash(sig_{k−1}(n), sorted sig_{k−1} of n's spawn/sync parents).
std::vector<std::vector<std::uint64_t>> wl_signatures(const Dtg& g, const DtgIndex& ix, int depth) {
  std::vector<std::vector<std::uint64_t>> sig(at(depth) + 1,
                                              std::vector<std::uint64_t>(g.nodes.size()));
  for (std::size_t n = 0; n < g.nodes.size(); ++n)
    sig[0][n] = vehicle::fnv1a((g.nodes[n].type == DtgNodeType::task ? "task:" : "sync:") +
                               g.nodes[n].kind);
  std::vector<std::uint64_t> ps;
  for (std::size_t k = 1; k <= at(depth); ++k)
    for (std::size_t n = 0; n < g.nodes.size(); ++n) {
      ps.clear();
      for (int p : ix.parents[n]) ps.push_back(sig[k - 1][at(p)]);
      std::sort(ps.begin(), ps.end());
      std::uint64_t h = mix(sig[k - 1][n], ps.size());
      for (std::uint64_t p : ps) h = mix(h, p);
      sig[k][n] = h;
    }
  return sig;
}

/// A DTG with its adjacency and signatures; refers to the graph, which must outlive it.
struct Graph {
  Graph(const Dtg& d, int depth)
      : g(d), ix(g), sig(wl_signatures(g, ix, depth)), mark(g.nodes.size(), 0) {}
  const Dtg& g;
  DtgIndex ix;
  std::vector<std::vector<std::uint64_t>> sig;
  // Visit marks of neighbourhood(): a node is seen in this walk when mark == epoch (no clearing;
  // a sync node awaiting a whole batch has hundreds of parents).
  mutable std::vector<std::uint32_t> mark;
  mutable std::uint32_t epoch = 0;
};

/// A located task node of a neighbourhood, with its canonical sort key.
struct Located {
  int depth;
  std::uint64_t sig;
  double dt_s;  // created relative to the root
  int number;
  Vec3 loc;
  auto key() const { return std::tie(depth, sig, dt_s, number); }
};

/// The located task nodes within `k` backward steps of `root`, in canonical order (depth,
/// signature at the remaining depth, creation time relative to the root, number).
std::vector<Located> neighbourhood(const Graph& gr, int root, int k) {
  std::vector<Located> out;
  if (++gr.epoch == 0) {  // wrapped: start the marks again
    std::fill(gr.mark.begin(), gr.mark.end(), 0);
    gr.epoch = 1;
  }
  gr.mark[at(root)] = gr.epoch;
  std::vector<int> level{root}, next;
  const double t0 = gr.g.nodes[at(root)].created_s;
  for (int d = 0; d <= k && !level.empty(); ++d) {
    next.clear();
    for (int n : level) {
      const DtgNode& node = gr.g.nodes[at(n)];
      if (node.type == DtgNodeType::task && node.first_loc_m)
        out.push_back(
            {d, gr.sig[at(k - d)][at(n)], node.created_s - t0, node.number, *node.first_loc_m});
      if (d < k)
        for (int p : gr.ix.parents[at(n)])
          if (gr.mark[at(p)] != gr.epoch) {
            gr.mark[at(p)] = gr.epoch;
            next.push_back(p);
          }
    }
    std::swap(level, next);
  }
  std::sort(out.begin(), out.end(),
            [](const Located& a, const Located& b) { return a.key() < b.key(); });
  return out;
}

/// A rigid motion of the plane (rotation by θ, then translation); z is carried unchanged.
struct Motion {
  double c = 1, s = 0, tx = 0, ty = 0;
  double rms_m = std::numeric_limits<double>::infinity();
  Vec3 apply(const Vec3& p) const { return {c * p.x - s * p.y + tx, s * p.x + c * p.y + ty, p.z}; }
};

/// The least-squares rigid motion carrying `from[i]` onto `to[i]` (closed form: the rotation
/// angle is atan2(Σ p×q, Σ p·q) of the centred pairs); translation only below two pairs.
Motion rigid_fit(const std::vector<Located>& from, const std::vector<Located>& to) {
  Motion m;
  const std::size_t n = std::min(from.size(), to.size());
  if (n == 0) return m;
  double px = 0, py = 0, qx = 0, qy = 0;
  for (std::size_t i = 0; i < n; ++i)
    px += from[i].loc.x, py += from[i].loc.y, qx += to[i].loc.x, qy += to[i].loc.y;
  const double dn = static_cast<double>(n);
  px /= dn, py /= dn, qx /= dn, qy /= dn;
  if (n >= 2) {
    double dot = 0, cross = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double ax = from[i].loc.x - px, ay = from[i].loc.y - py;
      const double bx = to[i].loc.x - qx, by = to[i].loc.y - qy;
      dot += ax * bx + ay * by;
      cross += ax * by - ay * bx;
    }
    const double theta = std::atan2(cross, dot);
    m.c = std::cos(theta), m.s = std::sin(theta);
  }
  m.tx = qx - (m.c * px - m.s * py);
  m.ty = qy - (m.s * px + m.c * py);
  double ss = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 p = m.apply(from[i].loc);
    ss += (p.x - to[i].loc.x) * (p.x - to[i].loc.x) + (p.y - to[i].loc.y) * (p.y - to[i].loc.y);
  }
  m.rms_m = std::sqrt(ss / dn);
  return m;
}

struct Ref {
  const Graph* graph;
  int node;
};

struct Point {
  std::string kind;
  Vec3 loc;
  double expected_s;
  int candidate;  // rank among the kept candidates
};

struct Cluster {
  std::string kind;
  Vec3 sum{0, 0, 0};
  double expected_sum_s = 0;
  int points = 0;
  std::vector<int> candidates;  // distinct
  Vec3 centre() const { return sum * (1.0 / points); }
};

/// Leader clustering in the points' fixed order: a point joins the first cluster of its kind
/// whose centre is within `radius_m` (horizontally).
std::vector<Cluster> cluster_points(const std::vector<Point>& points, double radius_m) {
  std::vector<Cluster> out;
  for (const Point& p : points) {
    Cluster* home = nullptr;
    for (Cluster& c : out) {
      const Vec3 m = c.centre();
      if (vehicle::horizontally_within(m, p.loc, radius_m) && c.kind == p.kind) {
        home = &c;
        break;
      }
    }
    if (!home) {
      home = &out.emplace_back();
      home->kind = p.kind;
    }
    home->sum += p.loc;
    home->expected_sum_s += p.expected_s;
    ++home->points;
    if (std::find(home->candidates.begin(), home->candidates.end(), p.candidate) ==
        home->candidates.end())
      home->candidates.push_back(p.candidate);
  }
  return out;
}

class Gmf final : public Forecaster {
 public:
  Gmf(std::vector<Dtg> histories, GmfSettings settings)
      : s_(settings), histories_(std::move(histories)) {
    s_.max_depth = std::clamp(s_.max_depth, 0, 64);
    index_.resize(at(s_.max_depth) + 1);
    graphs_.reserve(histories_.size());
    for (const Dtg& h : histories_) {
      q_.learn(h);
      graphs_.emplace_back(h, s_.max_depth);
    }
    for (const Graph& gr : graphs_)
      for (std::size_t n = 0; n < gr.g.nodes.size(); ++n)
        if (gr.ix.next_known[n])
          for (std::size_t k = 0; k < index_.size(); ++k)
            index_[k][gr.sig[k][n]].push_back({&gr, static_cast<int>(n)});
  }

  const char* name() const override { return "gmf"; }

  std::vector<ForecastRequest> forecast(const Dtg& current, double now_s) override {
    const Graph cur(current, s_.max_depth);
    std::vector<int> own;  // the current run's finished task nodes with a known next
    for (std::size_t n = 0; n < cur.g.nodes.size(); ++n)
      if (cur.ix.next_known[n]) own.push_back(static_cast<int>(n));
    std::vector<ForecastRequest> out;
    for (int f : frontier(cur.g, now_s)) merge(out, forecast_from(cur, own, f, now_s));
    std::sort(out.begin(), out.end(), [](const ForecastRequest& a, const ForecastRequest& b) {
      return std::tie(b.p, a.expected_s, a.location_m.x, a.location_m.y, a.kind) <
             std::tie(a.p, b.expected_s, b.location_m.x, b.location_m.y, b.kind);
    });
    return out;
  }

  double cancel_probability(const DtgNode& i, const DtgNode& j) const override {
    if (!i.first_loc_m || !j.first_loc_m) return 0;
    return q_.q(i.kind, j.kind, vehicle::horizontal_distance(*i.first_loc_m, *j.first_loc_m));
  }

 private:
  /// The newest running task nodes (creation time, then number), at most s_.frontier.
  std::vector<int> frontier(const Dtg& g, double now_s) const {
    std::vector<int> f;
    for (std::size_t n = 0; n < g.nodes.size(); ++n)
      if (g.nodes[n].type == DtgNodeType::task && g.nodes[n].status == DtgStatus::running &&
          g.nodes[n].created_s <= now_s)
        f.push_back(static_cast<int>(n));
    std::sort(f.begin(), f.end(), [&](int a, int b) {
      return std::tie(g.nodes[at(b)].created_s, g.nodes[at(b)].number) <
             std::tie(g.nodes[at(a)].created_s, g.nodes[at(a)].number);
    });
    if (f.size() > at(s_.frontier)) f.resize(at(std::max(0, s_.frontier)));
    return f;
  }

  /// The candidates whose depth-k signature equals f's: the stored runs' (their index bucket,
  /// not copied: it may hold tens of thousands), then the current run's.
  struct Matches {
    const std::vector<Ref>* stored = nullptr;
    std::vector<Ref> own;
    std::size_t size() const { return (stored ? stored->size() : 0) + own.size(); }
    const Ref& operator[](std::size_t i) const {
      const std::size_t n = stored ? stored->size() : 0;
      return i < n ? (*stored)[i] : own[i - n];
    }
  };
  Matches matches(const Graph& cur, const std::vector<int>& own, int f, int k) const {
    Matches m;
    const std::uint64_t sig = cur.sig[at(k)][at(f)];
    if (const auto it = index_[at(k)].find(sig); it != index_[at(k)].end()) m.stored = &it->second;
    for (int n : own)
      if (cur.sig[at(k)][at(n)] == sig) m.own.push_back({&cur, n});
    return m;
  }

  std::vector<ForecastRequest> forecast_from(const Graph& cur, const std::vector<int>& own, int f,
                                             double now_s) const {
    // Step 2: deepen while at least min_candidates remain; an empty level keeps the one before.
    Matches cands = matches(cur, own, f, 0);
    int depth = 0;
    for (int k = 1; k <= s_.max_depth && cands.size() >= at(s_.min_candidates); ++k) {
      Matches deeper = matches(cur, own, f, k);
      if (deeper.size() == 0) break;
      cands = std::move(deeper);
      depth = k;
    }
    if (cands.size() == 0) return {};
    // Step 3: rank by the residual of one rigid motion of the neighbourhoods.
    const std::vector<Located> mine = neighbourhood(cur, f, depth);
    const std::size_t ranked = std::min(cands.size(), at(std::max(1, s_.max_ranked)));
    std::vector<std::pair<Motion, Ref>> fits;
    for (std::size_t r = 0; r < ranked; ++r) {
      const Ref& c = cands[r * cands.size() / ranked];  // an even spread when capped
      Motion m = rigid_fit(stored_neighbourhood(c, depth), mine);
      if (std::isfinite(m.rms_m)) fits.emplace_back(m, c);
    }
    std::stable_sort(fits.begin(), fits.end(),
                     [](const auto& a, const auto& b) { return a.first.rms_m < b.first.rms_m; });
    // A match must carry its neighbourhood onto f's within the clustering radius: a worse one
    // would place its next beyond the radius that makes forecasts agree.
    std::erase_if(fits, [&](const auto& fit) { return fit.first.rms_m > s_.max_residual_m; });
    if (fits.size() > at(s_.top_k)) fits.resize(at(std::max(1, s_.top_k)));
    // Step 4: each candidate's next, carried over its motion, clustered.
    std::vector<Point> points;
    const double f_created = cur.g.nodes[at(f)].created_s;
    for (std::size_t r = 0; r < fits.size(); ++r) {
      const auto& [m, c] = fits[r];
      const DtgNode& cn = c.graph->g.nodes[at(c.node)];
      for (int k : c.graph->ix.next[at(c.node)]) {
        const DtgNode& nn = c.graph->g.nodes[at(k)];
        points.push_back({nn.kind, m.apply(*nn.first_loc_m),
                          f_created + (nn.created_s - cn.created_s), static_cast<int>(r)});
      }
    }
    std::vector<ForecastRequest> out;
    for (const Cluster& cl : cluster_points(points, s_.cluster_m))
      out.push_back({cl.kind, cl.centre(),
                     static_cast<double>(cl.candidates.size()) / static_cast<double>(fits.size()),
                     std::max(now_s, cl.expected_sum_s / cl.points)});
    return out;
  }

  /// A candidate's neighbourhood: a stored run's never changes, so it is kept (the same
  /// candidates come back for every frontier node and every forecast); the current run's is
  /// walked each time.
  const std::vector<Located>& stored_neighbourhood(const Ref& c, int depth) const {
    if (c.graph < graphs_.data() || c.graph >= graphs_.data() + graphs_.size()) {
      scratch_ = neighbourhood(*c.graph, c.node, depth);
      return scratch_;
    }
    const auto key = std::make_tuple(c.graph - graphs_.data(), c.node, depth);
    auto it = neighbourhoods_.find(key);
    if (it == neighbourhoods_.end())
      it = neighbourhoods_.emplace(key, neighbourhood(*c.graph, c.node, depth)).first;
    return it->second;
  }

  /// Across frontier nodes the larger probability wins for the same place and kind.
  void merge(std::vector<ForecastRequest>& into, std::vector<ForecastRequest> add) const {
    for (ForecastRequest& a : add) {
      auto same = std::find_if(into.begin(), into.end(), [&](const ForecastRequest& b) {
        return vehicle::horizontally_within(a.location_m, b.location_m, s_.cluster_m) &&
               b.kind == a.kind;
      });
      if (same == into.end())
        into.push_back(std::move(a));
      else if (a.p > same->p)
        *same = std::move(a);
    }
  }

  GmfSettings s_;
  std::vector<Dtg> histories_;  // graphs_ refer to these
  std::vector<Graph> graphs_;
  std::vector<std::unordered_map<std::uint64_t, std::vector<Ref>>> index_;
  CancellationModel q_;
  mutable std::map<std::tuple<std::ptrdiff_t, int, int>, std::vector<Located>> neighbourhoods_;
  mutable std::vector<Located> scratch_;
};

}  // namespace

std::unique_ptr<Forecaster> gmf_forecaster(std::vector<Dtg> histories, GmfSettings settings) {
  return std::make_unique<Gmf>(std::move(histories), settings);
}

}  // namespace swath::fleet
