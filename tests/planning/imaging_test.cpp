#include "swath/planning/imaging.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "swath/base/input_error.hpp"

namespace swath::planning {
namespace {

const Camera kQx1{"Sony ILCE-QX1", 23.2, 15.4, 16.0, 5456, 3632, std::nullopt};

TEST(Photogrammetry, Qx1At100MetresMatchesHandComputedFigures) {
  // GSD = 23.2 mm x 100 m / (16 mm x 5456 px) = 2.658 cm/px; footprint = 5456 x GSD by 3632 x GSD.
  PhotogrammetryMode m;
  m.altitude_m = 100;
  m.side_overlap = 0.7;
  m.front_overlap = 0.7;
  const Imaging im = photogrammetry_imaging(kQx1, m, ImageOrientation::landscape);
  EXPECT_NEAR(im.gsd_m * 100, 2.658, 0.0005);
  EXPECT_NEAR(im.footprint_across_m, 145.0, 1e-9);
  EXPECT_NEAR(im.footprint_along_m, 96.52, 0.005);
  EXPECT_NEAR(im.line_spacing_m, 43.5, 1e-9);
  EXPECT_NEAR(im.trigger_distance_m, 28.96, 0.005);
  EXPECT_FALSE(im.h_max_m);
}

TEST(Photogrammetry, GsdSetsTheAltitudeAndPortraitSwapsTheFootprint) {
  PhotogrammetryMode m;
  m.gsd_m = 0.02;
  m.side_overlap = 0.6;
  m.front_overlap = 0.8;
  const Imaging landscape = photogrammetry_imaging(kQx1, m, ImageOrientation::landscape);
  EXPECT_NEAR(landscape.altitude_m, 0.02 * 16 * 5456 / 23.2, 1e-9);  // 75.26 m
  EXPECT_NEAR(landscape.gsd_m, 0.02, 1e-15);
  const Imaging portrait = photogrammetry_imaging(kQx1, m, ImageOrientation::portrait);
  EXPECT_DOUBLE_EQ(portrait.footprint_across_m, landscape.footprint_along_m);
  EXPECT_DOUBLE_EQ(portrait.footprint_along_m, landscape.footprint_across_m);
  EXPECT_NEAR(portrait.line_spacing_m, 3632 * 0.02 * 0.4, 1e-9);
  EXPECT_NEAR(portrait.trigger_distance_m, 5456 * 0.02 * 0.2, 1e-9);
}

TEST(Detection, PaperEquationsFourToSix) {
  // 1 m x 2 m pattern over >= 20 px: h_max = 1 x 5456 / (2 x 20 x tan(fov/2)), tan(fov/2)
  // = 23.2/32.
  DetectionMode d{1.0, 2.0, 20.0, 0.5};
  const Imaging im = detection_imaging(kQx1, d, ImageOrientation::landscape);
  const double h_max = 1.0 * 5456 / (2 * 20 * (23.2 / 32));
  EXPECT_NEAR(*im.h_max_m, h_max, 1e-9);
  EXPECT_NEAR(*im.h_min_m, h_max / 2, 1e-9);
  EXPECT_NEAR(im.altitude_m, h_max * 1.5 / 2, 1e-9);
  const double step = 23.2 * h_max / (2 * 16);  // half the footprint at h_max
  EXPECT_NEAR(im.line_spacing_m, step, 1e-9);
  EXPECT_NEAR(im.footprint_across_m, step * 1.5, 1e-9);  // footprint at h = step (1 + v)
  // At h_max the pattern spans exactly min_pixels: GSD(h_max) = min(W, H) / C_p.
  EXPECT_NEAR(23.2 * h_max / (16 * 5456), 1.0 / 20, 1e-12);
}

TEST(Detection, OverlapEndsTouchAndDouble) {
  const Imaging zero = detection_imaging(kQx1, {2, 2, 10, 0.0}, ImageOrientation::landscape);
  EXPECT_NEAR(zero.footprint_across_m, zero.line_spacing_m, 1e-9);  // footprints touch
  EXPECT_NEAR(zero.altitude_m, *zero.h_min_m, 1e-9);
  const Imaging one = detection_imaging(kQx1, {2, 2, 10, 1.0}, ImageOrientation::landscape);
  EXPECT_NEAR(one.footprint_across_m, 2 * one.line_spacing_m, 1e-9);  // every point seen twice
  EXPECT_NEAR(one.altitude_m, *one.h_max_m, 1e-9);
}

TEST(Imaging, ImpossibleSettingsAreRefused) {
  Camera zero_focal = kQx1;
  zero_focal.focal_length_mm = 0;
  PhotogrammetryMode ok;
  ok.altitude_m = 50;
  EXPECT_THROW(photogrammetry_imaging(zero_focal, ok, ImageOrientation::landscape),
               base::InputError);
  PhotogrammetryMode overlap = ok;
  overlap.side_overlap = 1.0;
  EXPECT_THROW(photogrammetry_imaging(kQx1, overlap, ImageOrientation::landscape),
               base::InputError);
  PhotogrammetryMode both = ok;
  both.gsd_m = 0.01;
  EXPECT_THROW(photogrammetry_imaging(kQx1, both, ImageOrientation::landscape), base::InputError);
  PhotogrammetryMode negative;
  negative.altitude_m = -5;
  EXPECT_THROW(photogrammetry_imaging(kQx1, negative, ImageOrientation::landscape),
               base::InputError);
  EXPECT_THROW(detection_imaging(kQx1, {1, 1, 0, 0.5}, ImageOrientation::landscape),
               base::InputError);
  EXPECT_THROW(detection_imaging(kQx1, {1, 1, 10, 1.5}, ImageOrientation::landscape),
               base::InputError);
}

}  // namespace
}  // namespace swath::planning
