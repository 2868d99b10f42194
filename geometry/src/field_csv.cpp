// CSV: one position per line, "lon,lat" (or "x,y" metres with local_metres), an optional third
// column "ring" (0 = outer, 1.. = holes), an optional header naming the columns, '#' comments.
// Dialects: cells may be quoted (RFC 4180, "" inside quotes is a quote); the separator is ',', or
// ';' or a tab when the first line that is not a comment has no comma; lines end in LF, CRLF or a
// lone CR (old Mac).
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

std::optional<double> cell_number(std::string cell, char separator);

// The separator, from the first line that is not a comment: a comma (outside quotes) if it has
// one, else ';' or a tab if it has one, else a comma (a single column). A line of numbers with
// decimal commas between semicolons ("12,5;55,1", no header) is ';' too.
char detect_separator(std::string_view line) {
  bool quoted = false, comma = false, semicolon = false, tab = false;
  for (const char c : line) {
    if (c == '"') quoted = !quoted;
    if (quoted) continue;
    comma |= c == ',';
    semicolon |= c == ';';
    tab |= c == '\t';
  }
  if (comma && semicolon) {
    bool numbers = true;
    for (std::size_t start = 0; numbers && start <= line.size();) {
      const auto end = std::min(line.find(';', start), line.size());
      numbers = cell_number(trim(line.substr(start, end - start)), ';').has_value();
      start = end + 1;
    }
    if (numbers) return ';';
  }
  return comma ? ',' : semicolon ? ';' : tab ? '\t' : ',';
}

// "comma-separated" and the like, for messages.
std::string separated(char separator) {
  return separator == ';'    ? "semicolon-separated"
         : separator == '\t' ? "tab-separated"
                             : "comma-separated";
}

// The cells of a line split at `separator`, each trimmed; a cell in double quotes may hold the
// separator, and "" inside it is one quote. Text after a closing quote is refused.
std::vector<std::string> split(const std::string& line, char separator, const std::string& source,
                               const std::string& where) {
  std::vector<std::string> cells;
  std::size_t i = 0;
  while (true) {
    while (i < line.size() && line[i] != separator && (line[i] == ' ' || line[i] == '\t')) ++i;
    if (i < line.size() && line[i] == '"') {
      std::string cell;
      for (++i;; ++i) {
        if (i >= line.size())
          fail(source, where + ": column " + std::to_string(cells.size() + 1) +
                           " opens a quote that the line does not close");
        if (line[i] == '"') {
          if (i + 1 < line.size() && line[i + 1] == '"') {
            cell += '"';
            ++i;
            continue;
          }
          ++i;
          break;
        }
        cell += line[i];
      }
      while (i < line.size() && line[i] != separator && (line[i] == ' ' || line[i] == '\t')) ++i;
      if (i < line.size() && line[i] != separator)
        fail(source, where + ": column " + std::to_string(cells.size() + 1) +
                         " has text after its closing quote");
      cells.push_back(trim(cell));
    } else {
      const auto end = std::min(line.find(separator, i), line.size());
      cells.push_back(trim(std::string_view(line).substr(i, end - i)));
      i = end;
    }
    if (i >= line.size()) break;
    ++i;  // the separator
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

// A cell's number. With ';' as the separator a decimal comma ("12,5", as spreadsheets write it in
// much of Europe) is read as a decimal point, silently: a comma cannot separate columns in such a
// file, so "12,5" has no other reading. Only a cell with no '.' (a thousands separator as in
// "1.234,5" stays not a number rather than being guessed at).
std::optional<double> cell_number(std::string cell, char separator) {
  if (separator == ';' && cell.find('.') == std::string::npos)
    std::replace(cell.begin(), cell.end(), ',', '.');
  return number(cell);
}

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
  char separator = ',';

  std::map<long, std::size_t> ring_slot;  // ring id -> index in field.rings
  RawField field;
  std::size_t pos = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;  // UTF-8 BOM
  int line_no = 0;
  while (pos <= text.size()) {
    // A line ends at LF, CRLF or a lone CR.
    auto eol = text.find_first_of("\r\n", pos);
    if (eol == std::string::npos) eol = text.size();
    const std::string line = trim(std::string_view(text).substr(pos, eol - pos));
    pos = eol + (text.compare(eol, 2, "\r\n") == 0 ? 2 : 1);
    ++line_no;
    if (line.empty() || line[0] == '#') continue;
    const std::string where = "line " + std::to_string(line_no);
    if (first_data_line) separator = detect_separator(line);
    const std::vector<std::string> cells = split(line, separator, source, where);

    if (first_data_line) {
      first_data_line = false;
      if (!cell_number(cells[0], separator)) {
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
      fail(source, where + ": expected " + std::to_string(needed) + " " + separated(separator) +
                       " columns, found " + std::to_string(cells.size()));
    const auto x = cell_number(cells[cx], separator);
    const auto y = cell_number(cells[cy], separator);
    if (!x) fail(source, where + ": " + x_name + " '" + shown(cells[cx]) + "' is not a number");
    if (!y) fail(source, where + ": " + y_name + " '" + shown(cells[cy]) + "' is not a number");
    long ring_id = 0;
    if (cring) {
      const auto r = cell_number(cells[*cring], separator);
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
