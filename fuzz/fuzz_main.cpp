// The libFuzzer executable: SWATH_FUZZ_TARGET=<name> in the environment picks the target
// (fuzz/targets.cpp); `SWATH_FUZZ_TARGET=<name> swath_fuzz --print-seeds` lists its seed files
// (relative to the source tree) for scripts/fuzz.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <string>

#include "targets.hpp"

namespace {
const swath::fuzz::Target* target = nullptr;
}

extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) {
  const char* name = std::getenv("SWATH_FUZZ_TARGET");
  target = name ? swath::fuzz::find_target(name) : nullptr;
  if (target == nullptr) {
    std::cerr << "swath_fuzz: set SWATH_FUZZ_TARGET to one of:";
    for (const auto& t : swath::fuzz::targets()) std::cerr << " " << t.name;
    std::cerr << "\n";
    std::exit(2);
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
