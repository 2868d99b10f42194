#include "swath/render/legend.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "swath/render/image.hpp"

namespace swath::render {
namespace {

using geometry::Point2;

constexpr double kSmallestText_px = 7.0;

struct Layout {
  std::vector<std::string> texts;  ///< as drawn: all entries, or the first few and "+N more"
  double text_h = 0, cap_h = 0, row_h = 0, swatch = 0, gap = 0, pad = 0;
  std::size_t rows = 0, columns = 0;
  std::vector<double> column_width;  ///< text width of each column
  double width = 0, height = 0;
  bool fits(double max_width, double max_height) const {
    return width <= max_width && height <= max_height;
  }
};

Layout layout_at(std::vector<std::string> texts, double text_h, double max_height) {
  Layout l;
  l.texts = std::move(texts);
  l.text_h = text_h;
  l.cap_h = text_extent("H", text_h).height_px;
  l.row_h = std::ceil(1.6 * text_h);
  l.swatch = std::ceil(1.2 * text_h);
  l.gap = std::ceil(0.5 * text_h);
  l.pad = std::ceil(0.6 * text_h);
  const std::size_t n = l.texts.size();
  const double usable = max_height - 2 * l.pad;
  l.rows = std::max<std::size_t>(1, static_cast<std::size_t>(std::floor(usable / l.row_h)));
  l.rows = std::min(l.rows, n);
  l.columns = (n + l.rows - 1) / l.rows;
  l.rows = (n + l.columns - 1) / l.columns;  // balanced
  l.column_width.assign(l.columns, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    double& w = l.column_width[i / l.rows];
    w = std::max(w, static_cast<double>(text_extent(l.texts[i], text_h).width_px));
  }
  l.width = 2 * l.pad;
  for (std::size_t c = 0; c < l.columns; ++c)
    l.width += l.swatch + l.gap + l.column_width[c] + (c + 1 < l.columns ? 2 * l.gap : 0.0);
  l.height = 2 * l.pad + static_cast<double>(l.rows) * l.row_h;
  return l;
}

/// The legend at the largest text height that fits; at the smallest, one column of the first
/// entries and "+N more", then the longest texts cut with "..". Nothing fits: no texts.
Layout fitted_layout(const std::vector<LegendEntry>& entries, double max_width, double max_height,
                     double text_height_px) {
  std::vector<std::string> texts;
  for (const LegendEntry& e : entries) texts.push_back(e.text);
  double text_h = std::max(text_height_px, kSmallestText_px);
  Layout l = layout_at(texts, text_h, max_height);
  while (!l.fits(max_width, max_height) && text_h > kSmallestText_px) {
    text_h = std::max(kSmallestText_px, text_h - 0.5);
    l = layout_at(texts, text_h, max_height);
  }
  if (l.fits(max_width, max_height)) return l;
  if (l.columns > 1) {
    // One column of as many rows as fit, the last saying how many are left out.
    const auto fit_rows =
        static_cast<std::size_t>(std::max(1.0, std::floor((max_height - 2 * l.pad) / l.row_h)));
    const std::size_t keep = std::min(fit_rows, texts.size()) - 1;
    const std::size_t left_out = texts.size() - keep;
    texts.resize(keep);
    std::string more = "+";
    more += std::to_string(left_out);
    more += " more";
    texts.push_back(std::move(more));
    l = layout_at(texts, text_h, max_height);
  }
  while (!l.fits(max_width, max_height)) {
    auto longest = std::max_element(
        texts.begin(), texts.end(),
        [](const std::string& a, const std::string& b) { return a.size() < b.size(); });
    if (longest->size() <= 3 || l.height > max_height) return {};
    const bool cut = longest->size() >= 2 && longest->compare(longest->size() - 2, 2, "..") == 0;
    const std::size_t kept = longest->size() - (cut ? 3 : 1);
    *longest = std::string(longest->begin(), longest->begin() + static_cast<std::ptrdiff_t>(kept)) +
               std::string(2, '.');
    l = layout_at(texts, text_h, max_height);
  }
  return l;
}

std::vector<Point2> marker_outline(Point2 c, double size, MarkerShape shape) {
  const double h = size / 2;
  switch (shape) {
    case MarkerShape::square:
      return {{c.x - h, c.y - h}, {c.x + h, c.y - h}, {c.x + h, c.y + h}, {c.x - h, c.y + h}};
    case MarkerShape::triangle:
      return {{c.x, c.y - h}, {c.x + h, c.y + h}, {c.x - h, c.y + h}};
    case MarkerShape::disc:
      break;
  }
  std::vector<Point2> ring;
  for (int k = 0; k < 20; ++k) {
    const double a = 2 * M_PI * k / 20;
    ring.push_back({c.x + h * std::cos(a), c.y + h * std::sin(a)});
  }
  return ring;
}

void add_swatch(Scene& scene, const LegendEntry& e, double x, double y_mid, double size) {
  switch (e.kind) {
    case SwatchKind::fill:
      scene.screen_polygons.push_back({{{{x, y_mid - size / 2},
                                         {x + size, y_mid - size / 2},
                                         {x + size, y_mid + size / 2},
                                         {x, y_mid + size / 2}}},
                                       e.color,
                                       e.outline,
                                       1.5});
      break;
    case SwatchKind::line:
      scene.screen_polylines.push_back({{{x, y_mid}, {x + size, y_mid}}, 3, e.color});
      break;
    case SwatchKind::marker:
      scene.screen_polygons.push_back(
          {{marker_outline({x + size / 2, y_mid}, 0.85 * size, e.shape)}, e.color, e.outline, 1});
      break;
  }
}

}  // namespace

double fitted_text_height(const std::string& text, double width_px, double height_px) {
  double h = height_px;
  while (h > kSmallestText_px && text_extent(text, h).width_px > width_px) h -= 0.5;
  return std::max(h, kSmallestText_px);
}

LegendSize measure_legend(const std::vector<LegendEntry>& entries, double max_width_px,
                          double max_height_px, double text_height_px) {
  const Layout l = fitted_layout(entries, max_width_px, max_height_px, text_height_px);
  if (l.texts.empty()) return {};
  return {l.width, l.height, l.text_h};
}

PixelBox add_legend(Scene& scene, const std::vector<LegendEntry>& entries, const PixelBox& within,
                    Corner corner, double text_height_px) {
  PixelBox box{within.right_px, corner == Corner::top_right ? within.top_px : within.bottom_px,
               within.right_px, corner == Corner::top_right ? within.top_px : within.bottom_px};
  const Layout l = fitted_layout(entries, within.right_px - within.left_px,
                                 within.bottom_px - within.top_px, text_height_px);
  if (l.texts.empty()) return box;
  const double text_h = l.text_h;
  box.left_px = within.right_px - l.width;
  box.right_px = within.right_px;
  box.top_px = corner == Corner::top_right ? within.top_px : within.bottom_px - l.height;
  box.bottom_px = box.top_px + l.height;

  const Color ink{0.1f, 0.1f, 0.1f, 1};
  scene.screen_polygons.push_back({{{{box.left_px, box.top_px},
                                     {box.right_px, box.top_px},
                                     {box.right_px, box.bottom_px},
                                     {box.left_px, box.bottom_px}}},
                                   {1, 1, 1, 0.85f},
                                   {0.55f, 0.55f, 0.55f, 1},
                                   1});
  double x = box.left_px + l.pad;
  for (std::size_t c = 0; c < l.columns; ++c) {
    for (std::size_t r = 0; r < l.rows; ++r) {
      const std::size_t i = c * l.rows + r;
      if (i >= l.texts.size()) break;
      const double row_top = box.top_px + l.pad + static_cast<double>(r) * l.row_h;
      const double mid = row_top + l.row_h / 2;
      // "+N more" (the last of a shortened legend) has no swatch.
      if (i + 1 < l.texts.size() || l.texts.size() == entries.size())
        add_swatch(scene, entries[i], x, mid, l.swatch);
      // The capitals centred on the row.
      scene.labels.push_back({static_cast<int>(std::lround(x + l.swatch + l.gap)),
                              static_cast<int>(std::lround(mid + l.cap_h / 2)), l.texts[i], text_h,
                              ink});
    }
    x += l.swatch + l.gap + l.column_width[c] + 2 * l.gap;
  }
  return box;
}

}  // namespace swath::render
