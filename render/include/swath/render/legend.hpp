#pragma once
// Legends and text boxes measured with the font they are drawn in (text_extent), so that they fit
// inside the image at every size: a chart's series, a map's areas, lines and markers.

#include <string>
#include <vector>

#include "swath/render/scene.hpp"
#include "swath/render/view.hpp"

namespace swath::render {

/// What stands beside an entry's text: a filled square (areas), a short line (paths, series) or
/// a marker (home, start, end).
enum class SwatchKind { fill, line, marker };

struct LegendEntry {
  std::string text;
  SwatchKind kind = SwatchKind::fill;
  Color color;
  Color outline{0, 0, 0, 0};  ///< fill: alpha 0 for none
  MarkerShape shape = MarkerShape::disc;
};

/// Which corner of `within` the legend sits in.
enum class Corner { top_right, bottom_right };

/// The size a legend of these entries takes at `text_height_px`, shrunk (to 7 px text at the least)
/// until it fits `max_width_px` x `max_height_px` (rows in columns when too many for the height).
struct LegendSize {
  double width_px = 0, height_px = 0, text_height_px = 0;
};
LegendSize measure_legend(const std::vector<LegendEntry>& entries, double max_width_px,
                          double max_height_px, double text_height_px);

/// Adds a legend to the scene's screen layer and labels: a backing box (white, 85 % opaque, grey
/// outline), one row per entry, rows in columns when they do not fit the height of `within`. The
/// text height starts at `text_height_px` and shrinks (to 7 px at the least) until the box fits
/// `within`; the box returned is where it was drawn (empty entries: nothing drawn, an empty box at
/// the corner). Uses text_extent(): throws RenderError when the drawing module is missing.
PixelBox add_legend(Scene& scene, const std::vector<LegendEntry>& entries, const PixelBox& within,
                    Corner corner, double text_height_px);

/// The largest text height <= `height_px` (and >= 7 px) at which `text` is at most `width_px`
/// wide.
double fitted_text_height(const std::string& text, double width_px, double height_px);

}  // namespace swath::render
