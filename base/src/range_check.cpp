#include "swath/base/range_check.hpp"

#include <cmath>

#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"

namespace swath::base {

std::string value_text(double value) {
  return shortest_text(value);
}

void check_range(double value, const Range& range, const std::string& where) {
  if (std::isfinite(value) && value >= range.lo && value <= range.hi) return;
  // Built by append(): GCC 12 warns falsely (-Wrestrict, its bug 105329) on "x" + string here.
  std::string unit;
  if (!range.unit.empty()) unit.append(" ").append(range.unit);
  std::string message = where;
  message.append(" ").append(value_text(value)).append(unit);
  message.append(" is outside the range swath accepts, ").append(value_text(range.lo));
  message.append(" to ").append(value_text(range.hi)).append(unit);
  if (!range.why.empty()) message.append(" (").append(range.why).append(")");
  throw InputError(message);
}

}  // namespace swath::base
