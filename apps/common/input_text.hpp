#pragma once
// Reading what a command is given: whole input files, and option values of two numbers.

#include <optional>
#include <string>
#include <utility>

namespace swath::apps {

/// The whole file. Throws geometry::InputError "<path>: cannot open<why>" when it cannot be read;
/// `why` says what the file should have been (e.g. " the fleet file").
std::string read_input_file(const std::string& path, const std::string& why);

/// "A<separator>B" (spaces around either number allowed, nothing after) as two finite numbers.
std::optional<std::pair<double, double>> parse_number_pair(const std::string& text, char separator);

}  // namespace swath::apps
