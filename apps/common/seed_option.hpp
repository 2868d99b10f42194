#pragma once
// Seeds on the command line: decimal whole numbers from 0 to 2^53 − 1, so that every seed a
// program writes (summary.json, sweep and tune lines) reads back exactly from JSON. CLI11 alone
// would wrap "-1" to 2^64 − 1, clamp 18446744073709551616 and read "010" as octal.

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>

namespace swath::apps {

inline constexpr std::uint64_t kMaxSeed = (std::uint64_t{1} << 53) - 1;

/// A CLI11 check for a seed option (usage error, exit 2, when the text is not a seed).
inline CLI::Validator seed_check() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const std::string expected =
            "a seed is a whole number from 0 to 9007199254740991 (2^53 - 1), found '" + text + "'";
        if (text.empty() || text.size() > 16 ||
            text.find_first_not_of("0123456789") != std::string::npos)
          return expected;
        if (text.size() > 1 && text[0] == '0') return expected;  // no octal
        if (std::stoull(text) > kMaxSeed) return expected;
        return "";
      },
      "SEED", "seed");
}

}  // namespace swath::apps
