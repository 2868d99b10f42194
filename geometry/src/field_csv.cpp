// CSV: one position per line, "lon,lat" (or "x,y" metres with local_metres), an optional third
// column "ring" (0 = outer, 1.. = holes), an optional header naming the columns, '#' comments.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <optional>

#include "raw_field.hpp"

namespace swath::geometry::detail {
namespace {

std::string trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(" \t\r");
  return std::string(s.substr(b, e - b + 1));
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::size_t start = 0;
  while (true) {
    const auto comma = line.find(',', start);
    cells.push_back(trim(std::string_view(line).substr(start, comma - start)));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return cells;
}

std::optional<double> number(const std::string& cell) {
  double value = 0;
  const char* begin = cell.data();
  if (!cell.empty() && cell[0] == '+') ++begin;
  auto [end, error] = std::from_chars(begin, cell.data() + cell.size(), value);
  if (error != std::errc() || end != cell.data() + cell.size()) return std::nullopt;
  return value;
}

}  // namespace

RawField parse_csv(const std::string& text, const std::string& source, bool local_metres) {
  const std::string x_name = local_metres ? "x" : "lon";
  const std::string y_name = local_metres ? "y" : "lat";
  // Column positions of x (lon), y (lat) and ring; a header may reorder them.
  std::size_t cx = 0, cy = 1;
  std::optional<std::size_t> cring;
  bool first_data_line = true;

  std::map<long, std::size_t> ring_slot;  // ring id -> index in field.rings
  RawField field;
  std::size_t pos = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;  // UTF-8 BOM
  int line_no = 0;
  while (pos <= text.size()) {
    auto eol = text.find('\n', pos);
    if (eol == std::string::npos) eol = text.size();
    const std::string line = trim(std::string_view(text).substr(pos, eol - pos));
    pos = eol + 1;
    ++line_no;
    if (line.empty() || line[0] == '#') continue;
    const std::vector<std::string> cells = split(line);
    const std::string where = "line " + std::to_string(line_no);

    if (first_data_line) {
      first_data_line = false;
      if (!number(cells[0])) {
        // Header: find the columns by name.
        std::optional<std::size_t> hx, hy;
        for (std::size_t i = 0; i < cells.size(); ++i) {
          const std::string name = lower(cells[i]);
          if (local_metres ? name == "x" || name == "east" || name == "x_m"
                           : name == "lon" || name == "lng" || name == "longitude")
            hx = i;
          else if (local_metres ? name == "y" || name == "north" || name == "y_m"
                                : name == "lat" || name == "latitude")
            hy = i;
          else if (name == "ring")
            cring = i;
        }
        if (!hx || !hy) {
          const std::string what = source + ": " + where + ": the header must name the columns " +
                                   x_name + " and " + y_name;
          if (local_metres) throw InputError(what);
          throw InputError(what, {base::Remedy::local_csv});
        }
        cx = *hx;
        cy = *hy;
        continue;
      }
      if (cells.size() >= 3) cring = 2;
    }
    const std::size_t needed = std::max({cx, cy, cring.value_or(0)}) + 1;
    if (cells.size() < needed)
      fail(source, where + ": expected " + std::to_string(needed) +
                       " comma-separated columns, found " + std::to_string(cells.size()));
    const auto x = number(cells[cx]);
    const auto y = number(cells[cy]);
    if (!x) fail(source, where + ": " + x_name + " '" + shown(cells[cx]) + "' is not a number");
    if (!y) fail(source, where + ": " + y_name + " '" + shown(cells[cy]) + "' is not a number");
    long ring_id = 0;
    if (cring) {
      const auto r = number(cells[*cring]);
      if (!r || *r < 0 || *r > 1e9 || *r != std::floor(*r))
        fail(source, where + ": ring '" + shown(cells[*cring]) + "' is not a whole number >= 0");
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
  if (!ring_slot.count(0))
    fail(source, "no outer ring: ring 0 is the outer boundary, other ring numbers are holes");
  // Outer ring first, holes in order of their ring number.
  RawField ordered;
  for (const auto& [id, slot] : ring_slot) ordered.rings.push_back(std::move(field.rings[slot]));
  return ordered;
}

}  // namespace swath::geometry::detail
