// Douglas-Peucker on a ground profile (terrain.hpp).
#include "swath/planning/terrain.hpp"

#include <cmath>

namespace swath::planning {

std::vector<std::size_t> profile_breaks(const std::vector<double>& along_m,
                                        const std::vector<double>& height_m, double tolerance_m) {
  const std::size_t n = along_m.size();
  if (n < 2) return n == 1 ? std::vector<std::size_t>{0} : std::vector<std::size_t>{};
  std::vector<char> keep(n, 0);
  keep[0] = keep[n - 1] = 1;
  std::vector<std::pair<std::size_t, std::size_t>> todo{{0, n - 1}};  // no recursion depth limit
  while (!todo.empty()) {
    const auto [a, b] = todo.back();
    todo.pop_back();
    double worst = tolerance_m;
    std::size_t at = a;
    const double span = along_m[b] - along_m[a];
    for (std::size_t k = a + 1; k < b; ++k) {
      const double t = span > 0 ? (along_m[k] - along_m[a]) / span : 0.0;
      const double line = height_m[a] + t * (height_m[b] - height_m[a]);
      const double off = std::abs(height_m[k] - line);  // vertical: what the camera's height sees
      if (off > worst) {
        worst = off;
        at = k;
      }
    }
    if (at == a) continue;
    keep[at] = 1;
    todo.emplace_back(a, at);
    todo.emplace_back(at, b);
  }
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < n; ++k)
    if (keep[k]) out.push_back(k);
  return out;
}

const char* frame_name(AltitudeFrame frame) {
  switch (frame) {
    case AltitudeFrame::relative:
      return "relative";
    case AltitudeFrame::amsl:
      return "amsl";
    case AltitudeFrame::terrain:
      return "terrain";
  }
  return "relative";
}

}  // namespace swath::planning
