// libFuzzer harness over the array boundary: raw (V, F) with arbitrary indices and coordinates (NaN,
// inf, huge, denormal) into MeshTopology and its queries, find_chains, trace_chain/collect_base_meshes
// and -- now and then -- round_edges. A failure must be a RoundingError.
#include <Standard_Failure.hxx>
#include <cstdio>

#include "fuzz_input.h"
#include "meshround/chain.h"
#include "meshround/mesh.h"
#include "meshround/round.h"

using namespace meshround;

static double coordinate(fuzz::ByteReader& in) {
  switch (in.below(8)) {
    case 0: return in.raw_double();
    case 1: return double(int(in.below(5)) - 2);
    default: return in.below(5) + (in.u8() / 256.0) * (in.chance(128) ? 1 : 1e-9);  // a small lattice: shared edges, folds
  }
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::ByteReader in(data, size);
  const int n = in.below(40), m = in.below(60);
  Points V(n, 3);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) V(i, k) = coordinate(in);
  Triangles F(m, 3);
  for (int f = 0; f < m; ++f)
    for (int k = 0; k < 3; ++k) F(f, k) = in.chance(8) ? int(in.u32()) : (n > 0 ? in.below(n) : 0);
  std::vector<Vec3> seeds;
  for (int k = in.range(0, 2); k > 0; --k) seeds.push_back(Vec3(coordinate(in), coordinate(in), coordinate(in)));
  const double angle = in.chance(200) ? 30 : (in.chance(128) ? in.uniform(0, 180) : in.raw_double());
  const double search = in.chance(128) ? 0 : (in.chance(200) ? in.uniform(0, 10) : in.raw_double());
  const bool round = in.chance(48);
  try {
    const MeshTopology mesh(V, F);
    for (int f = 0; f < mesh.num_facets(); ++f) {
      (void)mesh.facet_normal(f), (void)mesh.facet_degenerate(f);
      for (int k = 0; k < 3; ++k) {
        const int a = F(f, k), b = F(f, (k + 1) % 3);
        int pair[2];
        (void)mesh.edge_facet_pair(a, b, pair);
        (void)mesh.neighbour(f, a, b), (void)mesh.dihedral_deg(a, b), (void)mesh.is_feature_edge(a, b, std::isfinite(angle) ? angle : 30);
      }
    }
    for (int v = 0; v < mesh.num_vertices(); ++v) (void)mesh.vertex_neighbours(v);
    if (!seeds.empty()) {
      const std::vector<SharpChain> chains = find_chains(V, F, seeds, angle, search);
      for (const SharpChain& c : chains) {
        const BaseMeshes base = collect_base_meshes(mesh, c, std::isfinite(search) && search > 0 ? search : 1.0, std::isfinite(angle) ? angle : 30);
        (void)base;
      }
      if (round) {
        RoundOptions o;
        o.radius = in.chance(128) ? in.uniform(0.01, 2) : coordinate(in);
        o.feature_angle_deg = angle;
        const Points V0 = V;
        const Triangles F0 = F;
        (void)round_edges(V, F, seeds, o);
        if (!(F.array() == F0.array()).all()) { std::fprintf(stderr, "FINDING: the input facets changed\n"); __builtin_trap(); }
      }
    }
  } catch (const RoundingError&) {
  } catch (const Standard_Failure& e) {
    std::fprintf(stderr, "FINDING: Standard_Failure escaped: %s\n", e.GetMessageString());
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
