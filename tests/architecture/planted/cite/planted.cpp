// Section marks planted for tests/architecture (never compiled): the lines the check must name.
#include <string>

namespace swath::control {

// The metrics of §17.4, every 1 ms.
constexpr int kMetricsPeriod_ns = 1'000'000;

/// Reads `controller.*` (§17.A).
int read_controller();

// Fine: paper 002 §7 names its paper; § alone, and §A without a digit, are no sections.
// Fine: "docs/swath-control.md, 'The simulated multirotor'" is the docs' own pointer.
const std::string kHelp = "the mission of §7";  // a string is not a comment: not checked

/* A block comment that cites §18.5 Example 5. */
int relief();

}  // namespace swath::control
