// libFuzzer harness for the solver-deck readers and writer (deck.h); the case is deck_case.h.
#include <cstdio>

#include "deck_case.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string finding = meshround::fuzz::deck_case(data, size);
  if (!finding.empty()) {
    std::fprintf(stderr, "FINDING: %s\n", finding.c_str());
    __builtin_trap();
  }
  return 0;
}
