// KML: the one <Polygon> of the document, <outerBoundaryIs> and any <innerBoundaryIs> rings of
// "lon,lat[,alt]" tuples separated by white space.
#include <pugixml.hpp>

#include <charconv>
#include <cstring>

#include "raw_field.hpp"

namespace swath::geometry::detail {
namespace {

std::string_view local_name(const pugi::xml_node& node) {
  std::string_view name = node.name();
  const auto colon = name.find(':');
  return colon == std::string_view::npos ? name : name.substr(colon + 1);
}

pugi::xml_node child(const pugi::xml_node& node, std::string_view name) {
  for (pugi::xml_node c : node.children())
    if (local_name(c) == name) return c;
  return {};
}

// Deeper nesting than any KML writer produces; a file nested 50,000 deep is refused instead of
// walked (docs/reliability.md).
constexpr int kMaxDepth = 256;

// Every element called `name`, in document order; iterative (no recursion on the file's depth).
void find_all(const pugi::xml_node& root, std::string_view name, std::vector<pugi::xml_node>& out,
              const std::string& text, const std::string& source) {
  std::vector<std::pair<pugi::xml_node, int>> stack;
  for (pugi::xml_node c = root.last_child(); c; c = c.previous_sibling()) stack.push_back({c, 1});
  while (!stack.empty()) {
    const auto [node, depth] = stack.back();
    stack.pop_back();
    if (node.type() != pugi::node_element) continue;
    if (depth > kMaxDepth)
      fail(source, "line " +
                       std::to_string(
                           line_column(text, static_cast<std::size_t>(node.offset_debug())).first) +
                       ": elements nested more than " + std::to_string(kMaxDepth) +
                       " levels deep; no KML writer does that");
    if (local_name(node) == name) out.push_back(node);
    for (pugi::xml_node c = node.last_child(); c; c = c.previous_sibling())
      stack.push_back({c, depth + 1});
  }
}

// Every child of `node` called `name`, in order.
std::vector<pugi::xml_node> children(const pugi::xml_node& node, std::string_view name) {
  std::vector<pugi::xml_node> out;
  for (pugi::xml_node c : node.children())
    if (local_name(c) == name) out.push_back(c);
  return out;
}

// One <LinearRing> of a boundary element (`boundary`, for the messages where the ring has no
// coordinates).
RawRing parse_ring(const pugi::xml_node& linear_ring, const pugi::xml_node& boundary,
                   const std::string& text, const std::string& source, const std::string& name) {
  const pugi::xml_node coordinates = child(linear_ring, "coordinates");
  const int boundary_line =
      line_column(text, static_cast<std::size_t>(boundary.offset_debug())).first;
  if (!coordinates)
    fail(source, "line " + std::to_string(boundary_line) + ": " + name +
                     " has no <LinearRing><coordinates>");
  RawRing ring;
  ring.name = name;
  // The element's text is all its text and CDATA children (a comment may split it); each piece
  // keeps the line it starts on, for the messages.
  std::string body;
  std::vector<std::size_t> piece_end;
  std::vector<int> piece_line;
  for (pugi::xml_node data : coordinates.children()) {
    if (data.type() != pugi::node_pcdata && data.type() != pugi::node_cdata) continue;
    body += data.value();
    piece_end.push_back(body.size());
    piece_line.push_back(line_column(text, static_cast<std::size_t>(data.offset_debug())).first);
  }
  std::size_t piece = 0;
  int line = piece_line.empty() ? boundary_line : piece_line[0];
  std::size_t i = 0;
  while (i < body.size()) {
    while (piece + 1 < piece_end.size() && i >= piece_end[piece]) line = piece_line[++piece];
    if (std::isspace(static_cast<unsigned char>(body[i]))) {
      if (body[i] == '\n') ++line;
      ++i;
      continue;
    }
    std::size_t end = i;
    while (end < body.size() && !std::isspace(static_cast<unsigned char>(body[end]))) ++end;
    const std::string tuple = body.substr(i, end - i);
    double values[3] = {0, 0, 0};
    int count = 0;
    const char* p = tuple.data();
    const char* stop = tuple.data() + tuple.size();
    bool ok = true;
    while (p < stop && count < 3) {
      auto [next, error] = std::from_chars(p, stop, values[count]);
      if (error != std::errc() || (next < stop && *next != ',')) {
        ok = false;
        break;
      }
      ++count;
      p = next < stop ? next + 1 : next;
    }
    if (!ok || count < 2 || p < stop)
      fail(source, "line " + std::to_string(line) + ": " + name + ": '" + shown(tuple) +
                       "' is not a lon,lat[,alt] tuple");
    ring.points.push_back({values[0], values[1]});
    ring.line.push_back(line);
    i = end;
  }
  return ring;
}

}  // namespace

RawField parse_kml(const std::string& text, const std::string& source) {
  pugi::xml_document doc;
  const pugi::xml_parse_result result = doc.load_buffer(text.data(), text.size());
  if (!result) {
    const auto [line, column] = line_column(text, static_cast<std::size_t>(result.offset));
    fail(source, "line " + std::to_string(line) + ", column " + std::to_string(column) +
                     ": invalid XML (" + result.description() + ")");
  }
  std::vector<pugi::xml_node> polygons;
  find_all(doc, "Polygon", polygons, text, source);
  if (polygons.empty()) fail(source, "the KML document has no <Polygon>");
  const auto line_of = [&](const pugi::xml_node& n) {
    return std::to_string(line_column(text, static_cast<std::size_t>(n.offset_debug())).first);
  };
  if (polygons.size() > 1)
    fail(source, "lines " + line_of(polygons[0]) + " and " + line_of(polygons[1]) +
                     " both hold a <Polygon>; choose one with --feature NAME or INDEX");
  const pugi::xml_node polygon = polygons[0];
  // One outer ring; every <LinearRing> of every <innerBoundaryIs> a hole (Google Earth takes
  // several in one): a ring left out would be a hole flown over, or ground not surveyed.
  const std::vector<pugi::xml_node> outers = children(polygon, "outerBoundaryIs");
  if (outers.empty())
    fail(source, "line " + line_of(polygon) + ": the <Polygon> has no <outerBoundaryIs>");
  const pugi::xml_node outer = outers[0];
  if (outers.size() > 1)
    fail(source, "lines " + line_of(outers[0]) + " and " + line_of(outers[1]) +
                     ": the <Polygon> has more than one <outerBoundaryIs>; give each part its "
                     "own <Placemark> and choose one with --feature NAME or INDEX");
  const std::vector<pugi::xml_node> outer_rings = children(outer, "LinearRing");
  if (outer_rings.size() > 1)
    fail(source, "line " + line_of(outer) +
                     ": the <outerBoundaryIs> holds more than one <LinearRing>; a polygon has "
                     "one outer boundary");
  RawField field;
  field.rings.push_back(parse_ring(outer_rings.empty() ? pugi::xml_node() : outer_rings[0], outer,
                                   text, source, "outer boundary"));
  std::size_t hole = 0;
  for (const pugi::xml_node& inner : children(polygon, "innerBoundaryIs")) {
    std::vector<pugi::xml_node> rings = children(inner, "LinearRing");
    if (rings.empty()) rings.emplace_back();  // refused by parse_ring: no <LinearRing>
    for (const pugi::xml_node& ring : rings)
      field.rings.push_back(
          parse_ring(ring, inner, text, source, "inner boundary " + std::to_string(hole++)));
  }
  return field;
}

}  // namespace swath::geometry::detail
