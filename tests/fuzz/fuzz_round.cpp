// libFuzzer harness: a generated mesh and options (fuzz_input.h) through round_edges. A success must be a
// sound mesh (sound.h) and leave the input arrays as they were; a failure must be a RoundingError.
// Anything else -- another exception, a sanitizer report, a hang (-timeout) -- is a finding.
#include "replay.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string finding = meshround::fuzz::round_case(data, size);
  if (!finding.empty()) {
    std::fprintf(stderr, "FINDING: %s\n", finding.c_str());
    __builtin_trap();
  }
  return 0;
}
