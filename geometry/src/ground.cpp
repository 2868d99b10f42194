// The DEM behind Ground, through the GIS module (ground.hpp).
#include "swath/geometry/ground.hpp"

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

 private:
  std::string path_;
  DemHeights heights_;
  double unit_m_ = 0.0;
  double resolution_m_ = 0.0;
  std::string geoid_;
};

}  // namespace

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
