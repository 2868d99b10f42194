#include "swath/geometry/field.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "swath/base/input_error.hpp"
#include "swath/geometry/classification.hpp"

namespace swath::geometry {

using base::InputError;
namespace {

// An expected-failure check: the message names the source and contains `fragment`.
void expect_error(const std::string& text, FieldFormat format, const std::string& fragment,
                  bool local = false) {
  try {
    parse_field(text, format, "area.in", local);
    ADD_FAILURE() << "accepted: " << text;
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("area.in: ", 0), 0u) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << "one sentence, one line: " << what;
  }
}

const char* kSquareRing = "[[8.0,47.0],[8.001,47.0],[8.001,47.001],[8.0,47.001],[8.0,47.0]]";

TEST(GeoJson, PolygonFeatureCollectionAndMultiPolygonGiveTheSameArea) {
  const std::string polygon =
      std::string(R"({"type":"Polygon","coordinates":[)") + kSquareRing + "]}";
  const std::string feature = R"({"type":"Feature","properties":{},"geometry":)" + polygon + "}";
  const std::string collection =
      R"({"type":"FeatureCollection","features":[{"type":"Feature","geometry":{"type":"Point","coordinates":[8,47]}},)" +
      feature + "]}";
  const std::string multi =
      std::string(R"({"type":"MultiPolygon","coordinates":[[)") + kSquareRing + "]]}";
  const double a = area(parse_field(polygon, FieldFormat::geojson, "p").polygon);
  // 0.001° of latitude ~ 111.2 m, of longitude at 47° ~ 76.0 m.
  EXPECT_NEAR(a, 111.2 * 76.0, 0.01 * 111.2 * 76.0);
  for (const std::string& text : {feature, collection, multi})
    EXPECT_DOUBLE_EQ(area(parse_field(text, FieldFormat::geojson, "p").polygon), a) << text;
}

TEST(GeoJson, UnclosedClockwiseRingIsNormalisedAndKeepsFilePositions) {
  const Field f = parse_field(
      R"({"type":"Polygon","coordinates":[[[8,47],[8,47.001],[8,47.001],[8.001,47.001],[8.001,47]]]})",
      FieldFormat::geojson, "p");
  ASSERT_EQ(f.polygon.outer.size(), 4u);
  EXPECT_GT(signed_area(f.polygon.outer), 0);
  EXPECT_EQ(f.source_index[0], (std::vector<std::size_t>{0, 4, 3, 1}));
  // Positions go back to the file's coordinates.
  const GeoPoint g = f.frame->to_geo(f.polygon.outer[1]);
  EXPECT_NEAR(g.lon_deg, 8.001, 1e-10);
  EXPECT_NEAR(g.lat_deg, 47.0, 1e-10);
}

// About a pole a ring turns one way on the ground and the other (or neither) in longitude and
// latitude: orientation is the local plane's. A square round the South Pole was read clockwise in
// one vertex order (every vertex reflex; the plan failed) and counter-clockwise in the other.
TEST(GeoJson, RingsRoundAPoleAreOrientedOnTheGround) {
  for (const double lat : {-89.995, 89.995}) {
    const std::string l = std::to_string(lat);
    const std::string east = "[[[45," + l + "],[135," + l + "],[-135," + l + "],[-45," + l + "]]]";
    const std::string west = "[[[45," + l + "],[-45," + l + "],[-135," + l + "],[135," + l + "]]]";
    std::vector<double> areas;
    for (const std::string& ring : {east, west}) {
      const Field f = parse_field(R"({"type":"Polygon","coordinates":)" + ring + "}",
                                  FieldFormat::geojson, "p");
      ASSERT_EQ(f.polygon.outer.size(), 4u) << lat;
      EXPECT_GT(signed_area(f.polygon.outer), 0) << lat << ring;
      EXPECT_EQ(classify(f.polygon).type, AreaType::convex) << lat << ring;
      // The vertices keep their file positions, the first first.
      EXPECT_EQ(f.source_index[0][0], 0u);
      for (std::size_t i = 0; i < 4; ++i) {
        const GeoPoint g = f.frame->to_geo(f.polygon.outer[i]);
        EXPECT_NEAR(g.lat_deg, lat, 1e-9);
      }
      areas.push_back(area(f.polygon));
    }
    // A square of half-diagonal 0.005 degrees of meridian (~556 m): ~6.2e5 m².
    EXPECT_NEAR(areas[0], areas[1], 1e-6 * areas[0]) << lat;
    EXPECT_NEAR(areas[0], 6.2e5, 0.02 * 6.2e5) << lat;
  }
}

// RFC 7946: an edge is straight in longitude and latitude. A 20 km edge along the 65th parallel
// bows 17 m from the local frame's chord between its ends: it is read with points along the
// parallel, each taking its edge's first vertex's number (within 0.5 m for the outer ring, 5 cm
// for a hole); the short sides are kept as they are.
TEST(GeoJson, LongEdgesAreReadStraightInLongitudeAndLatitude) {
  const Field f = parse_field(
      R"({"type":"Polygon","coordinates":[[[9.79,64.999],[10.21,64.999],[10.21,65.001],[9.79,65.001]],)"
      R"([[9.8,64.9995],[9.8,65.0005],[10.2,65.0005],[10.2,64.9995]]]})",
      FieldFormat::geojson, "p");
  ASSERT_EQ(f.polygon.holes.size(), 1u);
  for (std::size_t r = 0; r < 2; ++r) {
    const Ring& ring = r == 0 ? f.polygon.outer : f.polygon.holes[0];
    const std::vector<double> parallels =
        r == 0 ? std::vector<double>{64.999, 65.001} : std::vector<double>{64.9995, 65.0005};
    const double tolerance_m = r == 0 ? 0.5 : 0.05;
    ASSERT_GT(ring.size(), 8u) << r;
    ASSERT_EQ(f.geo_rings[r].size(), ring.size());
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const GeoPoint g = f.frame->to_geo(ring[i]);
      EXPECT_TRUE(std::abs(g.lat_deg - parallels[0]) < 1e-9 ||
                  std::abs(g.lat_deg - parallels[1]) < 1e-9)
          << r << " " << i << ": " << g.lat_deg;
      EXPECT_NEAR(g.lat_deg, f.geo_rings[r][i].lat_deg, 1e-9);
      EXPECT_LT(f.source_index[r][i], 4u);
    }
    // Every chord along a parallel strays from it within the tolerance: its middle's latitude.
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const GeoPoint a = f.frame->to_geo(ring[i]), b = f.frame->to_geo(ring[(i + 1) % ring.size()]);
      if (std::abs(a.lat_deg - b.lat_deg) > 1e-9) continue;  // a short north-south side
      const GeoPoint m = f.frame->to_geo((ring[i] + ring[(i + 1) % ring.size()]) * 0.5);
      EXPECT_LT(std::abs(m.lat_deg - a.lat_deg) * 111360, tolerance_m) << r << " " << i;
    }
  }
}

TEST(GeoJson, HolesAreClockwiseAndSubtracted) {
  const Field f = parse_field(
      R"({"type":"Polygon","coordinates":[[[0,0],[0.01,0],[0.01,0.01],[0,0.01]],[[0.002,0.002],[0.004,0.002],[0.004,0.004],[0.002,0.004]]]})",
      FieldFormat::geojson, "p");
  ASSERT_EQ(f.polygon.holes.size(), 1u);
  EXPECT_LT(signed_area(f.polygon.holes[0]), 0);
  EXPECT_NEAR(area(f.polygon) / std::abs(signed_area(f.polygon.outer)), 1 - 0.04, 1e-4);
}

TEST(GeoJson, BadInputIsNamedWithItsPlace) {
  expect_error("", FieldFormat::geojson, "empty");
  expect_error("{\"type\": \"Polygon\",\n \"coordinates\": [[[0,0],[1,0]", FieldFormat::geojson,
               "line 2");
  expect_error("[1,2]", FieldFormat::geojson, "no \"type\"");
  expect_error(R"({"type":"LineString","coordinates":[[0,0],[1,1]]})", FieldFormat::geojson,
               "the GeoJSON's geometry is a LineString; an area must be a Polygon");
  expect_error(R"({"type":"polygon","coordinates":[[[0,0],[1,0],[1,1]]]})", FieldFormat::geojson,
               "is a polygon; an area must be a Polygon or a MultiPolygon with one part (GeoJSON's "
               "type names are case-sensitive)");
  expect_error(R"({"type":"Feature","geometry":{"type":"GeometryCollection","geometries":[]}})",
               FieldFormat::geojson, "the Feature's geometry is a GeometryCollection");
  expect_error(R"({"type":"FeatureCollection","features":[]})", FieldFormat::geojson, "no Polygon");
  expect_error(R"({"type":"Polygon","coordinates":[[[0,0],[1,0],[0,0]]]})", FieldFormat::geojson,
               "2 distinct vertices");
  expect_error(R"({"type":"Polygon","coordinates":[[[0,0],[1,0],[2,0],[0,0]]]})",
               FieldFormat::geojson, "no area (its vertices lie on one line)");
  // On one parallel: curved in the local plane, still no area.
  expect_error(R"({"type":"Polygon","coordinates":[[[8,47],[8.001,47],[8.002,47]]]})",
               FieldFormat::geojson, "no area");
  expect_error(R"({"type":"Polygon","coordinates":[[[0,0],[1,0],[1,1e999]]]})",
               FieldFormat::geojson, "invalid JSON (number overflow parsing '1e999')");
  expect_error(R"({"type":"Polygon","coordinates":[[[8,47],[8,95.5],[9,47]]]})",
               FieldFormat::geojson, "position 1: latitude 95.5 is beyond");
  expect_error(R"({"type":"Polygon","coordinates":[[[8,47],["8",48],[9,47]]]})",
               FieldFormat::geojson, "ring 0), position 1");
  expect_error(
      R"({"type":"Polygon","coordinates":[[[0,0],[0.01,0],[0.01,0.01],[0,0.01]],[[0.02,0.02],[0.03,0.02],[0.03,0.03]]]})",
      FieldFormat::geojson, "hole 0 (ring 1) is a hole that lies outside the outer ring");
  expect_error(std::string(R"({"type":"MultiPolygon","coordinates":[[)") + kSquareRing + "],[" +
                   kSquareRing + "]]}",
               FieldFormat::geojson, "2 parts");
}

TEST(Kml, OuterAndInnerBoundariesWithNamespacePrefix) {
  const std::string kml = R"(<?xml version="1.0"?>
<kml:kml xmlns:kml="http://www.opengis.net/kml/2.2"><kml:Placemark><kml:Polygon>
 <kml:outerBoundaryIs><kml:LinearRing><kml:coordinates>
   0,0,0 0.01,0,0 0.01,0.01,0 0,0.01,0 0,0,0
 </kml:coordinates></kml:LinearRing></kml:outerBoundaryIs>
 <kml:innerBoundaryIs><kml:LinearRing><kml:coordinates>0.002,0.002 0.004,0.002 0.004,0.004</kml:coordinates></kml:LinearRing></kml:innerBoundaryIs>
</kml:Polygon></kml:Placemark></kml:kml>)";
  const Field f = parse_field(kml, FieldFormat::kml, "k");
  EXPECT_EQ(f.polygon.outer.size(), 4u);
  ASSERT_EQ(f.polygon.holes.size(), 1u);
  EXPECT_EQ(f.polygon.holes[0].size(), 3u);
  EXPECT_EQ(classify(f.polygon).type, AreaType::concave);
}

// Google Earth writes several <LinearRing> in one <innerBoundaryIs>; each is a hole (the second
// was dropped, and the drone flew over it). Two outer boundaries are refused, not half read.
TEST(Kml, EveryRingOfAnInnerBoundaryIsAHole) {
  const std::string kml = R"(<kml><Placemark><Polygon>
 <outerBoundaryIs><LinearRing><coordinates>0,0 0.01,0 0.01,0.01 0,0.01 0,0</coordinates></LinearRing></outerBoundaryIs>
 <innerBoundaryIs>
  <LinearRing><coordinates>0.002,0.002 0.004,0.002 0.004,0.004</coordinates></LinearRing>
  <LinearRing><coordinates>0.006,0.006 0.008,0.006 0.008,0.008 0.006,0.008</coordinates></LinearRing>
 </innerBoundaryIs>
 <innerBoundaryIs><LinearRing><coordinates>0.002,0.007 0.003,0.007 0.003,0.008</coordinates></LinearRing></innerBoundaryIs>
</Polygon></Placemark></kml>)";
  const Field f = parse_field(kml, FieldFormat::kml, "k");
  ASSERT_EQ(f.polygon.holes.size(), 3u);
  EXPECT_EQ(f.polygon.holes[0].size(), 3u);
  EXPECT_EQ(f.polygon.holes[1].size(), 4u);
  EXPECT_EQ(f.polygon.holes[2].size(), 3u);
  expect_error(
      "<kml><Polygon><outerBoundaryIs><LinearRing><coordinates>0,0 1,0 1,1</coordinates>"
      "</LinearRing></outerBoundaryIs>\n<outerBoundaryIs><LinearRing><coordinates>2,0 3,0 3,1"
      "</coordinates></LinearRing></outerBoundaryIs></Polygon></kml>",
      FieldFormat::kml, "lines 1 and 2: the <Polygon> has more than one <outerBoundaryIs>");
  expect_error(
      "<kml><Polygon><outerBoundaryIs><LinearRing><coordinates>0,0 1,0 1,1</coordinates>"
      "</LinearRing><LinearRing><coordinates>2,0 3,0 3,1</coordinates></LinearRing>"
      "</outerBoundaryIs></Polygon></kml>",
      FieldFormat::kml, "holds more than one <LinearRing>");
  expect_error(
      "<kml><Polygon><outerBoundaryIs><LinearRing><coordinates>0,0 1,0 1,1</coordinates>"
      "</LinearRing></outerBoundaryIs><innerBoundaryIs/></Polygon></kml>",
      FieldFormat::kml, "inner boundary 0 has no <LinearRing><coordinates>");
}

TEST(Kml, BadInputNamesTheLine) {
  expect_error("<kml><Polygon>\n<outerBoundaryIs>\n</kml>", FieldFormat::kml, "line 3");
  expect_error("<kml><Placemark/></kml>", FieldFormat::kml, "no <Polygon>");
  expect_error(
      "<kml><Polygon><outerBoundaryIs><LinearRing><coordinates>\n0,0 1,0\n1,x "
      "0,1\n</coordinates></LinearRing></outerBoundaryIs></Polygon></kml>",
      FieldFormat::kml, "line 3: outer boundary: '1,x' is not a lon,lat[,alt] tuple");
  expect_error(
      "<kml><Polygon><outerBoundaryIs><LinearRing><coordinates>\n0,0 1,0\n1,91 "
      "0,1\n</coordinates></LinearRing></outerBoundaryIs></Polygon></kml>",
      FieldFormat::kml, "outer boundary, position 2 (line 3): latitude 91");
  expect_error("<kml><Polygon></Polygon></kml>", FieldFormat::kml, "no <outerBoundaryIs>");
}

// Issue 16: 50,000 nested elements crashed the recursive walk; now refused at 256 levels.
TEST(Kml, DeepNestingIsRefusedNotWalkedRecursively) {
  std::string deep = "<kml>";
  for (int i = 0; i < 50000; ++i) deep += "<Folder>";
  deep += "<Polygon/>";
  for (int i = 0; i < 50000; ++i) deep += "</Folder>";
  deep += "</kml>";
  expect_error(deep, FieldFormat::kml, "line 1: elements nested more than 256 levels deep");
  // 200 levels are fine (no KML writer nests that deep, but it is not malicious).
  std::string nested = "<kml>";
  for (int i = 0; i < 200; ++i) nested += "<Folder>";
  nested += R"(<Polygon><outerBoundaryIs><LinearRing><coordinates>8,47 8.001,47 8.001,47.001
               </coordinates></LinearRing></outerBoundaryIs></Polygon>)";
  for (int i = 0; i < 200; ++i) nested += "</Folder>";
  EXPECT_EQ(parse_field(nested + "</kml>", FieldFormat::kml, "n").polygon.outer.size(), 3u);
}

// Issue 16: a comment or CDATA inside <coordinates> silently dropped the vertices after it.
TEST(Kml, CoordinatesSplitByCommentsAndCdataKeepEveryVertex) {
  const std::string kml = R"(<kml><Placemark><Polygon><outerBoundaryIs><LinearRing><coordinates>
8.0,47.0 8.001,47.0 <!-- a comment -->
8.001,47.001 <![CDATA[8.0005,47.0015]]>
8.0,47.001 8.0,47.0
<!-- more --> </coordinates></LinearRing></outerBoundaryIs></Polygon></Placemark></kml>)";
  const Field f = parse_field(kml, FieldFormat::kml, "split.kml");
  EXPECT_EQ(f.polygon.outer.size(), 5u);
  // A bad tuple after the comment is named on its own line (line 4).
  std::string bad = kml;
  bad.replace(bad.find("8.0,47.001 8.0,47.0"), 10, "8.0;47.001");
  expect_error(bad, FieldFormat::kml, "line 4: outer boundary: '8.0;47.001' is not a lon,lat");
}

// Issue 16: a field across the antimeridian was planned 11,900 km away (the frame's origin was
// the mean longitude, about 0). Unwrapped, it is the same field as its twin shifted east by 10°.
TEST(Geodesy, AFieldAcrossTheAntimeridianIsTheFieldShiftedAway) {
  const auto field_at = [](double lon_west, double lon_east) {
    const std::string ring = "[[" + std::to_string(lon_west) + ",-16.5],[" +
                             std::to_string(lon_east) + ",-16.5],[" + std::to_string(lon_east) +
                             ",-16.49],[" + std::to_string(lon_west) + ",-16.49],[" +
                             std::to_string(lon_west) + ",-16.5]]";
    return parse_field(R"({"type":"Polygon","coordinates":[)" + ring + "]}", FieldFormat::geojson,
                       "a");
  };
  const Field across = field_at(179.99, -179.99), shifted = field_at(169.99, 170.01);
  EXPECT_NEAR(area(across.polygon), area(shifted.polygon), 1e-6 * area(shifted.polygon));
  EXPECT_NEAR(area(across.polygon), 2.36e6, 0.02e6);  // 2.13 km x 1.11 km
  // The frame's origin is in the field, and the file's own positions are kept for the outputs.
  EXPECT_NEAR(std::abs(across.frame->origin().lon_deg), 180.0, 0.011);
  int east = 0, west = 0;
  for (const GeoPoint& g : across.geo_rings[0]) {
    east += g.lon_deg == -179.99;
    west += g.lon_deg == 179.99;
  }
  EXPECT_EQ(east, 2);
  EXPECT_EQ(west, 2);
  for (const Point2& p : across.polygon.outer) EXPECT_LT(std::hypot(p.x, p.y), 2000.0);
  // ±180 is one meridian: a quadrilateral with vertices on both is convex.
  const Field meridian = parse_field(
      R"({"type":"Polygon","coordinates":[[[179.99,-16.5],[180,-16.49],[-180,-16.48],[179.98,-16.49],[179.99,-16.5]]]})",
      FieldFormat::geojson, "m");
  EXPECT_EQ(classify(meridian.polygon).type, AreaType::convex);
}

TEST(Geodesy, NestedHolesAreRefusedNamingBoth) {
  expect_error(R"({"type":"Polygon","coordinates":[
      [[8.50,47.40],[8.51,47.40],[8.51,47.41],[8.50,47.41],[8.50,47.40]],
      [[8.502,47.402],[8.502,47.408],[8.508,47.408],[8.508,47.402],[8.502,47.402]],
      [[8.504,47.404],[8.504,47.406],[8.506,47.406],[8.506,47.404],[8.504,47.404]]]})",
               FieldFormat::geojson,
               "hole 1 (ring 2) lies inside the Polygon, hole 0 (ring 1); nested holes");
}

TEST(Csv, HeaderColumnsInAnyOrderRingsBomAndCrlf) {
  const Field f = parse_field(
      "\xEF\xBB\xBF# comment\r\nlat,lon,ring\r\n47,8,0\r\n47,8.01,0\r\n47.01,8.01,0\r\n\r\n"
      "47.002,8.002,1\r\n47.004,8.002,1\r\n47.004,8.004,1\r\n",
      FieldFormat::csv, "c");
  ASSERT_EQ(f.polygon.holes.size(), 1u);
  EXPECT_EQ(f.polygon.outer.size(), 3u);
  EXPECT_NEAR(f.frame->to_geo(f.polygon.outer[1]).lon_deg, 8.01, 1e-9);
}

TEST(Csv, LocalMetresNeedNoFrame) {
  const Field f = parse_field("0,0\n100,0\n100,50\n0,50\n", FieldFormat::csv, "c", true);
  EXPECT_FALSE(f.frame);
  EXPECT_DOUBLE_EQ(area(f.polygon), 5000.0);
  EXPECT_EQ(f.polygon.outer[2], (Point2{100, 50}));
}

TEST(Csv, BadInputNamesTheLine) {
  expect_error("# only a comment\n", FieldFormat::csv, "no positions");
  expect_error("lon,lat\n8,47\n8.1,x\n", FieldFormat::csv, "line 3: lat 'x' is not a number");
  // A NUL or control character in the cell is shown as '?': the message stays one whole sentence.
  expect_error(std::string("lon,lat\n8,47\n8.1,-33.9\0\x1b\n", 25), FieldFormat::csv,
               "line 3: lat '-33.9?\?' is not a number");
  expect_error("8,47\n8.1\n", FieldFormat::csv,
               "line 2: expected 2 comma-separated columns, found 1");
  expect_error("8,47\nnan,47.1\n8.2,47\n", FieldFormat::csv,
               "position 1 (line 2): coordinate is not a finite number");
  expect_error("8,47\ninf,47.1\n8.2,47\n", FieldFormat::csv, "not a finite number");
  expect_error("east,north\n0,0\n", FieldFormat::csv, "header must name the columns lon and lat");
  expect_error("8,47,1\n8.1,47,1\n8.1,47.1,1\n", FieldFormat::csv, "no outer ring");
  expect_error("0,0\n1,0\n", FieldFormat::csv, "2 distinct vertices", true);
}

// The tester's square near Cape Town (lon, lat), read back from each dialect: quoted cells (one
// holding a comma, one a doubled quote), ';' with decimal commas (with and without a header), tab,
// CR-only line ends.
void expect_cape_square(const std::string& text) {
  SCOPED_TRACE(text);
  const Field f = parse_field(text, FieldFormat::csv, "c");
  ASSERT_EQ(f.geo_rings.size(), 1u);
  ASSERT_EQ(f.geo_rings[0].size(), 4u);
  EXPECT_EQ(f.geo_rings[0][0].lon_deg, 18.4);
  EXPECT_EQ(f.geo_rings[0][0].lat_deg, -33.9);
  EXPECT_EQ(f.geo_rings[0][1].lon_deg, 18.40324686);
  EXPECT_EQ(f.geo_rings[0][2].lat_deg, -33.898203378);
  EXPECT_EQ(f.geo_rings[0][3].lon_deg, 18.4);
}

TEST(Csv, QuotedSemicolonTabAndCrOnlyDialectsReadTheSamePositions) {
  expect_cape_square(
      "\"lon\",\"lat\"\n\"18.4\",\"-33.9\"\n\"18.40324686\",\"-33.9\"\n"
      "\"18.40324686\",\"-33.898203378\"\n\"18.4\",\"-33.898203378\"\n");
  expect_cape_square(
      "id,name,lat,lon,alt\n1,\"a, b\",-33.9,18.4,100\n2,\"say \"\"hi\"\", b\",-33.9,18.40324686,"
      "100\n3, \"c\" ,-33.898203378,18.40324686,100\n4,d,-33.898203378,18.4,100\n");
  expect_cape_square(
      "lat;lon\n-33.9;18.4\n-33.9;18.40324686\n-33.898203378;18.40324686\n"
      "-33.898203378;18.4\n");
  expect_cape_square(
      "lat;lon\n-33,9;18,4\n-33,9;18,40324686\n-33,898203378;18,40324686\n"
      "-33,898203378;18,4\n");
  expect_cape_square(
      "18,4;-33,9\n18,40324686;-33,9\n18,40324686;-33,898203378\n18,4;-33,898203378\n");
  expect_cape_square(
      "lat\tlon\n-33.9\t18.4\n-33.9\t18.40324686\n-33.898203378\t18.40324686\n"
      "-33.898203378\t18.4\n");
  expect_cape_square(
      "lon,lat\r18.4,-33.9\r18.40324686,-33.9\r18.40324686,-33.898203378\r"
      "18.4,-33.898203378\r");
  // Comments after the values (a tester's "12.5,55.1 # corner" was refused), with each separator;
  // a '#' inside a quoted cell is text (were it a comment, the line would lose its lat and lon).
  expect_cape_square(
      "# the tester's square\nlon,lat # degrees\n18.4,-33.9 # south-west\n18.40324686,-33.9#se\n"
      "18.40324686,-33.898203378  # north-east\n18.4,-33.898203378\t# north-west\n");
  expect_cape_square(
      "lat;lon # decimal commas\n-33,9;18,4 # a, b\n-33,9;18,40324686 #\n"
      "-33,898203378;18,40324686\n-33,898203378;18,4 # end\n");
  expect_cape_square(
      "name,lat,lon\n\"plot #4, south-west\",-33.9,18.4 # corner\n\"#2\",-33.9,18.40324686\n"
      "\"a \"\"#\"\"\", -33.898203378 ,18.40324686\n#4,-33.898203378,18.4\n"
      "\"#5\",-33.898203378,18.4\n");
  expect_error("lon,lat\n18.4,-33.9 # corner\n18.5 # ,-33.9\n", FieldFormat::csv,
               "line 3: expected 2 comma-separated columns, found 1");
  // A lone CR and CRLF each end one line: the line numbers stay right.
  expect_error("lon,lat\r\r8,47\r\n8.1,x\r", FieldFormat::csv, "line 4: lat 'x' is not a number");
  expect_error("lat;lon\n47;8\n47,1;x\n", FieldFormat::csv, "line 3: lon 'x' is not a number");
  expect_error("lat\tlon\n47\n", FieldFormat::csv,
               "line 2: expected 2 tab-separated columns, found 1");
}

TEST(Csv, DialectRefusalsSayWhatWasAssumed) {
  expect_error("lon,lat,lat\n18.4,-33.9,-33.9\n", FieldFormat::csv,
               "line 1: the header names the latitude column twice: 'lat' (column 2) and 'lat' "
               "(column 3)");
  expect_error("lon,longitude,lat\n", FieldFormat::csv,
               "the header names the longitude column twice: 'lon' (column 1) and 'longitude'");
  expect_error("WKT,name\n\"POLYGON((18.4 -33.9,18.41 -33.9,18.41 -33.89,18.4 -33.9))\",a\n",
               FieldFormat::csv,
               "line 1: the header must name the columns lon and lat (lng, longitude and latitude "
               "are taken too); it names WKT, name");
  expect_error("lat;lon,alt\n-33.9;18.4,1\n", FieldFormat::csv,
               "it names lat;lon, alt; the separator is taken from the first line: a comma if it "
               "has one, else ';' or a tab");
  expect_error("lon,lat\n0,0\n", FieldFormat::csv,
               "header must name the columns x and y (east and north, or x_m and y_m, are taken "
               "too); it names lon, lat",
               true);
  // No header, three columns: the third is read as the ring number, and the message says so.
  expect_error("18.4,-33.9,12\n18.41,-33.9,12\n18.41,-33.89,12\n", FieldFormat::csv,
               "no outer ring: with no header the third column is read as the ring number");
  expect_error("18.4,-33.9,12.5\n18.41,-33.9,12.5\n18.41,-33.89,12.5\n", FieldFormat::csv,
               "line 1: the third column '12.5' is not a whole number >= 0; with no header a third "
               "column is read as the ring number (0 = outer, 1.. = holes): give a header line "
               "naming the columns (lon,lat,...)");
  expect_error("lon,lat\n\"18.4,-33.9\n", FieldFormat::csv,
               "line 2: column 1 opens a quote that the line does not close");
  expect_error("lon,lat\n\"18.4\"5,-33.9\n", FieldFormat::csv,
               "line 2: column 1 has text after its closing quote");
  // A thousands separator is not guessed at: "1.234,5" is no number.
  expect_error("x;y\n1.234,5;0\n", FieldFormat::csv, "line 2: x '1.234,5' is not a number", true);
}

TEST(ReadField, FileErrors) {
  try {
    read_field("/nonexistent/field.geojson");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/field.geojson: cannot open"),
              std::string::npos);
  }
  EXPECT_THROW(read_field("field.shp"), InputError);
}

}  // namespace
}  // namespace swath::geometry
