// libFuzzer harness: a generated mesh rounded by round_edges, then its rounds made again at another radius
// (or sharpened) by change_radius. A success must be a sound mesh (sound.h) against the rounded one and
// leave it as it was; a failure must be a RoundingError. Anything else is a finding.
#include "replay.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string finding = meshround::fuzz::reround_case(data, size);
  if (!finding.empty()) {
    std::fprintf(stderr, "FINDING: %s\n", finding.c_str());
    __builtin_trap();
  }
  return 0;
}
