#include "swath/planning/limits.hpp"

#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"

namespace swath::planning::limits {

void check_overlap(double value, const std::string& where) {
  if (value > 1 && value <= 100)
    throw base::InputError(where + " " + base::value_text(value) +
                           " looks like a percentage; overlaps are fractions: did you mean " +
                           base::fixed_text(value / 100, 2) + "?");
  base::check_range(value, kOverlap, where);
}

}  // namespace swath::planning::limits
