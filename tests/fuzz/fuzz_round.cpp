// libFuzzer harness: a generated mesh and options (fuzz_input.h) through round_edges.
// A success must be a sound mesh (sound.h) and leave the input arrays as they were; a failure must be a
// RoundingError. Anything else -- another exception, a sanitizer report, a hang -- is a finding.
#include <Standard_Failure.hxx>
#include <cstdio>
#include <cstdlib>

#include "fuzz_input.h"
#include "meshround/round.h"
#include "sound.h"

using namespace meshround;

static bool verbose() {
  static const bool v = std::getenv("MESHROUND_FUZZ_VERBOSE") != nullptr;
  return v;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const fuzz::FuzzCase c = fuzz::decode_case(data, size);
  if (c.F.rows() > 6000) return -1;  // keep executions fast (the decoder's bounds keep it under this)
  const Points V0 = c.V;
  const Triangles F0 = c.F;
  if (verbose())
    std::fprintf(stderr, "mesh %ld v %ld f, element %g, seeds %zu, r %g (law %zu), tol %g, angle %g, reach %g\n", long(c.V.rows()),
                 long(c.F.rows()), c.element, c.seeds.size(), c.options.radius, c.options.radius_law.size(), c.options.tolerance,
                 c.options.feature_angle_deg, c.options.reach);
  try {
    const RoundResult res = round_edges(c.V, c.F, c.seeds, c.options);
    if (!(c.V.array() == V0.array()).all() && !(c.V.hasNaN() && V0.hasNaN())) { std::fprintf(stderr, "FINDING: the input vertices changed\n"); __builtin_trap(); }
    if (!(c.F.array() == F0.array()).all()) { std::fprintf(stderr, "FINDING: the input facets changed\n"); __builtin_trap(); }
    fuzz::SoundnessInput s{c.V, c.F, res.vertices, res.triangles, {}, 0};
    for (const RoundedChain& ch : res.chains)
      if (!ch.chain.empty()) s.chain_ends.push_back(ch.chain.front()), s.chain_ends.push_back(ch.chain.back());
    double rmax = c.options.radius;
    for (const RadiusControl& rc : c.options.radius_law) rmax = std::max(rmax, rc.radius);
    s.end_allowance = 1.5 * c.options.reach * rmax;
    const std::string bad = fuzz::check_sound(s);
    if (verbose()) std::fprintf(stderr, "rounded: %ld facets, %s\n", long(res.triangles.rows()), bad.empty() ? "sound" : bad.c_str());
    if (!bad.empty()) {
      std::fprintf(stderr, "FINDING: unsound result: %s\n", bad.c_str());
      __builtin_trap();
    }
  } catch (const RoundingError& e) {
    if (verbose()) std::fprintf(stderr, "refused (%s): %s\n", error_code_name(e.code), e.what());
    if (!(c.V.array() == V0.array()).all() && !(c.V.hasNaN() && V0.hasNaN())) { std::fprintf(stderr, "FINDING: the input vertices changed\n"); __builtin_trap(); }
  } catch (const Standard_Failure& e) {
    std::fprintf(stderr, "FINDING: Standard_Failure escaped: %s: %s\n", e.DynamicType()->Name(), e.GetMessageString());
    __builtin_trap();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "FINDING: std::exception escaped: %s\n", e.what());
    __builtin_trap();
  } catch (...) {
    std::fprintf(stderr, "FINDING: unknown exception escaped\n");
    __builtin_trap();
  }
  return 0;
}
