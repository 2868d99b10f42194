#pragma once
// The remedies libraries name (base::Remedy), worded in the programs' own options.

#include <string>
#include <vector>

#include "swath/base/input_error.hpp"

namespace swath::apps {

/// `what` with its remedies worded: "; add drones or battery, or give --allow-partial".
std::string with_remedies(const std::string& what, const std::vector<base::Remedy>& remedies);

}  // namespace swath::apps
