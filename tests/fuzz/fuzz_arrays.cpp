// libFuzzer harness over the array boundary: raw (V, F) with arbitrary indices and coordinates into
// MeshTopology, find_chains, collect_base_meshes and round_edges. A failure must be a RoundingError.
#include "replay.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string finding = meshround::fuzz::arrays_case(data, size);
  if (!finding.empty()) {
    std::fprintf(stderr, "FINDING: %s\n", finding.c_str());
    __builtin_trap();
  }
  return 0;
}
