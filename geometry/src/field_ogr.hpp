#pragma once
// Internal: the GDAL/OGR reader behind read_field (GDAL's headers stay in field_ogr.cpp).

#include <string>

#include "raw_field.hpp"
#include "swath/geometry/field.hpp"

namespace swath::geometry::detail {

/// The one area `options` choose from a file OGR opens, as WGS84 longitude/latitude rings.
/// Throws InputError: the file cannot be opened, no or several layers/areas without a choice
/// (listing the names), an unknown layer/feature/field, a non-area geometry, a CRS without a
/// transformation to WGS84.
RawField read_ogr(const std::string& path, const FieldReadOptions& options);

/// The areas of the layer `options` choose (names and positions), for swath batch.
std::vector<AreaEntry> list_ogr_areas(const std::string& path, const FieldReadOptions& options);

/// How many layers of `path` read_ogr() read with GDAL in this process (field.hpp's
/// area_file_reads()).
std::size_t area_reads(const std::string& path);

/// One WKT geometry (POLYGON, MULTIPOLYGON of one part, a closed LINESTRING) in longitude/latitude.
RawField parse_wkt(const std::string& text, const std::string& source);

}  // namespace swath::geometry::detail
