#pragma once
// A plan of stages for a lawnmower survey (tests and bench): lanes of `length_m` up and down at
// x = 0, spacing, 2 spacing, .., joined by half circles; its power repeats every two lanes.

#include <cmath>
#include <string>

namespace swath::test {

inline std::string lawnmower_plan(int lanes, double spacing_m, double length_m) {
  std::string s;
  auto num = [](double v) {
    std::string t = std::to_string(v);
    return t;
  };
  const double r = spacing_m / 2;
  for (int i = 0; i < lanes; ++i) {
    const double x = i * spacing_m;
    const bool up = i % 2 == 0;
    // The lane: phi = x - x_i; +90 turns grad (east) to north.
    s += "0.05; " + std::string(up ? "90" : "270") + "; x-(" + num(x) + ")\n";
    s += num(x) + ", " + num(up ? length_m : 0.0) + "\n[0, 0]\n[2, 10]\n";
    if (i + 1 == lanes) break;
    // The turn: a half circle over the top (clockwise) or under the bottom (counter-clockwise).
    const double cx = x + r, cy = up ? length_m : 0.0;
    s += "0.002; " + std::string(up ? "270" : "90") + "; (x-(" + num(cx) + "))^2+(y-(" + num(cy) +
         "))^2-" + num(r * r) + "\n";
    s += num(x + spacing_m) + ", " + num(cy) + "\n[0, 0]\n[2, 10]\n";
  }
  return s;
}

}  // namespace swath::test
