#pragma once
// What each libFuzzer target does with its input: one reader of swath's, fed arbitrary bytes.
// Bad input must end in base::InputError (the one-sentence error, exit 2); anything else that
// escapes (another exception, a crash, a sanitizer report, a hang) is a bug. Shared by the fuzz
// executables and by the regression test that replays every input the fuzzers ever broke.

#include <string>
#include <vector>

namespace swath::fuzz {

struct Target {
  const char* name;                       ///< SWATH_FUZZ_TARGET=<name>, tests/fuzz-regressions/<name>/
  void (*run)(const std::string& input);  ///< throws only what is a bug
  std::vector<const char*> seeds;         ///< seed corpus, paths relative to the source tree
};

/// Every target, in a fixed order.
const std::vector<Target>& targets();

/// The target called `name`, or nullptr.
const Target* find_target(const std::string& name);

}  // namespace swath::fuzz
