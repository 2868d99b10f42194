// CSV: one position per line, "lon,lat" (or "x,y" metres with local_metres), an optional third
// column "ring" (0 = outer, 1.. = holes), an optional header naming the columns, '#' comments
// (whole lines, or after the values). The dialects (quoted cells, ';' or tab separators, decimal
// commas between semicolons, LF, CRLF or lone CR line ends) are base::CsvText's.
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include "raw_field.hpp"
#include "swath/base/csv_text.hpp"

namespace swath::geometry::detail {
namespace {

std::string names_text(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size() && i < 10; ++i)
    out += (i ? ", " : "") + (names[i].empty() ? std::string("(empty)") : shown(names[i]));
  if (names.size() > 10) out += " and " + std::to_string(names.size() - 10) + " more";
  return out;
}

}  // namespace

RawField parse_csv(const std::string& text, const std::string& source, bool local_metres) {
  const std::string x_name = local_metres ? "x" : "lon";
  const std::string y_name = local_metres ? "y" : "lat";
  // Column positions of x (lon), y (lat) and ring; a header may reorder them.
  std::size_t cx = 0, cy = 1;
  std::optional<std::size_t> cring;
  bool first_data_line = true;
  bool ring_assumed = false;  // no header, three or more columns: the third read as the ring

  std::map<long, std::size_t> ring_slot;  // ring id -> index in field.rings
  RawField field;
  base::CsvText csv(text, source);
  while (csv.next()) {
    const int line_no = csv.line();
    const std::string where = "line " + std::to_string(line_no);
    const char separator = csv.separator();
    const std::vector<std::string>& cells = csv.cells();

    if (first_data_line) {
      first_data_line = false;
      if (!csv.number(cells[0])) {
        // Header: find the columns by name; a column named twice is refused.
        std::optional<std::size_t> hx, hy;
        auto take = [&](std::optional<std::size_t>& column, std::size_t i, const char* role) {
          if (column)
            fail(source, where + ": the header names the " + role + " column twice: '" +
                             shown(cells[*column]) + "' (column " + std::to_string(*column + 1) +
                             ") and '" + shown(cells[i]) + "' (column " + std::to_string(i + 1) +
                             ")");
          column = i;
        };
        for (std::size_t i = 0; i < cells.size(); ++i) {
          const std::string name = lower(cells[i]);
          if (local_metres ? name == "x" || name == "east" || name == "x_m"
                           : name == "lon" || name == "lng" || name == "longitude")
            take(hx, i, local_metres ? "x" : "longitude");
          else if (local_metres ? name == "y" || name == "north" || name == "y_m"
                                : name == "lat" || name == "latitude")
            take(hy, i, local_metres ? "y" : "latitude");
          else if (name == "ring")
            take(cring, i, "ring");
        }
        if (!hx || !hy) {
          std::string what = source + ": " + where + ": the header must name the columns " +
                             x_name + " and " + y_name +
                             (local_metres ? " (east and north, or x_m and y_m, are taken too)"
                                           : " (lng, longitude and latitude are taken too)") +
                             "; it names " + names_text(cells);
          const bool other_separator =
              std::any_of(cells.begin(), cells.end(), [](const std::string& c) {
                return c.find(';') != std::string::npos || c.find('\t') != std::string::npos;
              });
          if (other_separator)
            what +=
                "; the separator is taken from the first line: a comma if it has one, else "
                "';' or a tab";
          if (local_metres) throw InputError(what);
          throw InputError(what, {base::Remedy::local_csv});
        }
        cx = *hx;
        cy = *hy;
        continue;
      }
      if (cells.size() >= 3) cring = 2, ring_assumed = true;
    }
    const std::size_t needed = std::max({cx, cy, cring.value_or(0)}) + 1;
    if (cells.size() < needed)
      fail(source, where + ": expected " + std::to_string(needed) + " " +
                       base::separated_text(separator) + " columns, found " +
                       std::to_string(cells.size()));
    const auto x = csv.number(cells[cx]);
    const auto y = csv.number(cells[cy]);
    if (!x) fail(source, where + ": " + x_name + " '" + shown(cells[cx]) + "' is not a number");
    if (!y) fail(source, where + ": " + y_name + " '" + shown(cells[cy]) + "' is not a number");
    long ring_id = 0;
    if (cring) {
      const auto r = csv.number(cells[*cring]);
      if (!r || *r < 0 || *r > 1e9 || *r != std::floor(*r)) {
        if (ring_assumed)
          fail(source, where + ": the third column '" + shown(cells[*cring]) +
                           "' is not a whole number >= 0; with no header a third column is read "
                           "as the ring number (0 = outer, 1.. = holes): give a header line "
                           "naming the columns (" +
                           x_name + "," + y_name + ",...) if it is something else");
        fail(source, where + ": ring '" + shown(cells[*cring]) + "' is not a whole number >= 0");
      }
      ring_id = static_cast<long>(*r);
    }
    auto [slot, added] = ring_slot.try_emplace(ring_id, field.rings.size());
    if (added) {
      field.rings.push_back({});
      field.rings.back().name =
          ring_id == 0 ? "outer ring (ring 0)" : "hole ring " + std::to_string(ring_id);
    }
    RawRing& ring = field.rings[slot->second];
    ring.points.push_back({*x, *y});
    ring.line.push_back(line_no);
  }
  if (field.rings.empty()) fail(source, "no positions (the file has only comments or a header)");
  if (!ring_slot.count(0)) {
    if (ring_assumed)
      fail(source,
           "no outer ring: with no header the third column is read as the ring number, "
           "and no line has ring 0 (the outer boundary; 1.. are holes); give a header "
           "line naming the columns (" +
               x_name + "," + y_name + ",...) if the third column is something else");
    fail(source, "no outer ring: ring 0 is the outer boundary, other ring numbers are holes");
  }
  // Outer ring first, holes in order of their ring number.
  RawField ordered;
  for (const auto& [id, slot] : ring_slot) ordered.rings.push_back(std::move(field.rings[slot]));
  return ordered;
}

}  // namespace swath::geometry::detail
