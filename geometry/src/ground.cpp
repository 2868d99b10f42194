// The DEM behind Ground, through the GIS module (ground.hpp).
#include "swath/geometry/ground.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "swath/geometry/geotiff.hpp"

#include "gis_module.hpp"
#include "swath/base/input_error.hpp"

namespace swath::geometry {
namespace {

std::vector<double> sample(const std::string& path, const std::vector<GeoPoint>& points,
                           double unit_m = 0.0, double* resolution_m = nullptr) {
  std::vector<double> values;
  double resolution = 0.0;
  std::string error;
  if (!detail::gis_module().sample(path, unit_m, points, values, resolution, error))
    throw base::InputError(error);
  if (resolution_m) *resolution_m = resolution;
  return values;
}

std::vector<double> bends_of(const std::string& path, double unit_m, const GeoPoint& a,
                             const GeoPoint& b) {
  std::vector<double> fractions;
  std::string error;
  if (!detail::gis_module().bends(path, unit_m, a, b, fractions, error))
    throw base::InputError(error);
  return fractions;
}

std::string geoid_grid() {
  std::string path, error;
  if (!detail::gis_module().grid("egm96_15.gtx", path, error)) throw base::InputError(error);
  return path;
}

class DemGround final : public Ground {
 public:
  DemGround(std::string path, DemHeights heights, double unit_m)
      : path_(std::move(path)), heights_(heights), unit_m_(unit_m) {
    sample(path_, {}, unit_m_, &resolution_m_);  // opens it: a bad file fails here, before planning
    if (heights_ == DemHeights::ellipsoid) geoid_ = geoid_grid();
  }
  std::vector<double> heights_m(const std::vector<GeoPoint>& points) const override {
    std::vector<double> h = sample(path_, points, unit_m_);
    if (heights_ == DemHeights::ellipsoid) {
      const std::vector<double> n = sample(geoid_, points);
      for (std::size_t k = 0; k < h.size(); ++k) h[k] -= n[k];
    }
    return h;
  }
  double resolution_m() const override { return resolution_m_; }
  std::string source() const override { return path_; }
  std::optional<std::vector<double>> bends(const GeoPoint& a, const GeoPoint& b) const override {
    std::vector<double> f = bends_of(path_, unit_m_, a, b);
    if (heights_ == DemHeights::ellipsoid) {  // the geoid's grid is bilinear too: its bends count
      const std::vector<double> n = bends_of(geoid_, 0.0, a, b);
      f.insert(f.end(), n.begin(), n.end());
      std::sort(f.begin(), f.end());
    }
    return f;
  }

 private:
  std::string path_;
  DemHeights heights_;
  double unit_m_ = 0.0;
  double resolution_m_ = 0.0;
  std::string geoid_;
};

// The quadratic through three samples (t_mid strictly between; otherwise the straight line).
GroundProfile::Piece piece_through(double t0, double g0, double tm, double gm, double t1,
                                   double g1) {
  GroundProfile::Piece p{t0, t1, tm, g0, 0, 0};
  if (!(tm > t0 && tm < t1)) {
    p.slope_m = t1 > t0 ? (g1 - g0) / (t1 - t0) : 0.0;
    return p;
  }
  p.slope_m = (gm - g0) / (tm - t0);
  p.curve_m = ((g1 - gm) / (t1 - tm) - p.slope_m) / (t1 - t0);
  return p;
}

// Samples closer than this (metres along the leg) are one.
constexpr double kSameSample_m = 1e-6;

}  // namespace

std::optional<std::vector<double>> Ground::bends(const GeoPoint&, const GeoPoint&) const {
  return std::nullopt;
}

std::size_t GroundProfile::add(double at) {
  auto piece = std::upper_bound(pieces.begin(), pieces.end(), at,
                                [](double x, const Piece& p) { return x < p.t1; });
  if (piece == pieces.end()) --piece;
  const auto k = static_cast<std::size_t>(std::lower_bound(t.begin(), t.end(), at) - t.begin());
  t.insert(t.begin() + static_cast<std::ptrdiff_t>(k), at);
  ground_m.insert(ground_m.begin() + static_cast<std::ptrdiff_t>(k), piece->at(at));
  return k;
}

GroundProfile ground_profile(const Ground& ground, const std::function<GeoPoint(double)>& at,
                             double length_m) {
  constexpr double kStretch_m = 100.0;
  const auto n =
      static_cast<std::size_t>(std::max(1.0, std::ceil(length_m / ground.resolution_m())));
  std::vector<double> ts;
  for (std::size_t k = 0; k <= n; ++k)
    ts.push_back(static_cast<double>(k) / static_cast<double>(n));
  // Piece ends: the ground's bends and the stretches' ends; a sample half way between each two,
  // so that each piece has the three samples its quadratic needs.
  std::vector<double> ends{0.0};
  const auto stretches = static_cast<std::size_t>(std::max(1.0, std::ceil(length_m / kStretch_m)));
  bool known = true;
  for (std::size_t s = 0; s < stretches && known; ++s) {
    const double t0 = static_cast<double>(s) / static_cast<double>(stretches);
    const double t1 = static_cast<double>(s + 1) / static_cast<double>(stretches);
    const auto b = length_m > 0 ? ground.bends(at(t0), at(t1)) : std::vector<double>{};
    known = b.has_value();
    if (known)
      for (const double f : *b) ends.push_back(t0 + f * (t1 - t0));
    ends.push_back(t1);
  }
  if (known)
    for (std::size_t k = 0; k + 1 < ends.size(); ++k) {
      ts.push_back(ends[k]);
      ts.push_back(0.5 * (ends[k] + ends[k + 1]));
    }
  std::sort(ts.begin(), ts.end());
  GroundProfile out;
  for (const double t : ts)
    if (out.t.empty() || (t - out.t.back()) * length_m > kSameSample_m) out.t.push_back(t);
  if (out.t.size() < 2) out.t = {0.0, 1.0};
  out.t.back() = 1.0;
  std::vector<GeoPoint> geo;
  for (const double t : out.t) geo.push_back(at(t));
  out.ground_m = ground.heights_m(geo);
  const auto index = [&](double t) {  // the sample nearest t
    auto it = std::lower_bound(out.t.begin(), out.t.end(), t);
    if (it == out.t.end() || (it != out.t.begin() && t - *(it - 1) < *it - t)) --it;
    return static_cast<std::size_t>(it - out.t.begin());
  };
  const auto& g = out.ground_m;
  if (!known) {  // straight between samples
    for (std::size_t k = 0; k + 1 < out.t.size(); ++k)
      out.pieces.push_back(piece_through(out.t[k], g[k], out.t[k], g[k], out.t[k + 1], g[k + 1]));
    return out;
  }
  for (std::size_t k = 0; k + 1 < ends.size(); ++k) {
    const std::size_t a = index(ends[k]), b = index(ends[k + 1]);
    if (b <= a) continue;
    const std::size_t m = index(0.5 * (ends[k] + ends[k + 1]));
    out.pieces.push_back(piece_through(out.t[a], g[a], out.t[m], g[m], out.t[b], g[b]));
  }
  return out;
}

HeightAboveGround height_above_ground(const GroundProfile& profile, std::size_t first,
                                      std::size_t last, double z_first_m, double z_last_m) {
  const double ta = profile.t[first], tb = profile.t[last];
  const double rise = tb > ta ? (z_last_m - z_first_m) / (tb - ta) : 0.0;
  const auto line = [&](double t) { return z_first_m + rise * (t - ta); };
  HeightAboveGround out{std::numeric_limits<double>::infinity(),
                        -std::numeric_limits<double>::infinity(), ta, ta};
  const auto consider = [&](double t, double ground) {
    const double above = line(t) - ground;
    if (above < out.least_m) out.least_m = above, out.t_least = t;
    if (above > out.most_m) out.most_m = above, out.t_most = t;
  };
  for (std::size_t k = first; k <= last; ++k) consider(profile.t[k], profile.ground_m[k]);
  // Within a curved piece the line's height above it is extreme where the ground's slope is
  // the line's: a hump between two samples is where a leg dips.
  for (const GroundProfile::Piece& p : profile.pieces) {
    if (p.t1 <= ta || p.t0 >= tb || p.curve_m == 0) continue;
    const double t = ((rise - p.slope_m) / p.curve_m + p.t0 + p.t_mid) / 2;
    if (t > std::max(ta, p.t0) && t < std::min(tb, p.t1)) consider(t, p.at(t));
  }
  return out;
}

std::shared_ptr<const Ground> dem_ground(const std::string& path, DemHeights heights,
                                         double unit_m) {
  return std::make_shared<DemGround>(path, heights, unit_m);
}

double dem_unit_m(const std::string& name) {
  if (name == "m") return 1.0;
  if (name == "ft") return kFoot_m;
  if (name == "us-ft") return kUsSurveyFoot_m;
  return 0.0;
}

DemReads dem_reads(const std::string& path) {
  return detail::gis_module().reads(path);
}

void forget_dem(const std::string& path) {
  detail::gis_module().forget(path);
}

std::string geotiff_bytes(const LocalRaster& raster) {
  std::string bytes, error;
  if (!detail::gis_module().geotiff(raster, bytes, error)) throw std::runtime_error(error);
  return bytes;
}

std::vector<double> geoid_undulation_m(const std::vector<GeoPoint>& points) {
  return sample(geoid_grid(), points);
}

}  // namespace swath::geometry
