// One libFuzzer executable per target: SWATH_FUZZ_TARGET names it (fuzz/CMakeLists.txt).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <string>

#include "targets.hpp"

namespace {
const swath::fuzz::Target* target = nullptr;
}

// `fuzz_NAME --print-seeds` lists the seed files (relative to the source tree) for scripts/fuzz.
extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) {
  target = swath::fuzz::find_target(SWATH_FUZZ_TARGET);
  if (target == nullptr) {
    std::cerr << "no fuzz target '" << SWATH_FUZZ_TARGET << "'\n";
    std::abort();
  }
  if (*argc == 2 && std::string((*argv)[1]) == "--print-seeds") {
    for (const char* seed : target->seeds) std::cout << seed << '\n';
    std::exit(0);
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  target->run(std::string(reinterpret_cast<const char*>(data), size));
  return 0;
}
