#pragma once

#include <stdexcept>
#include <string>

namespace swath::geometry {

/// Bad input from a user's file or arguments. what() is one sentence naming the file, the place
/// (line, feature, key) and the problem; the command line turns it into exit code 2.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace swath::geometry
