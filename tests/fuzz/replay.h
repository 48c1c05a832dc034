// The two fuzz targets' bodies, shared with their regression tests (tests/cpp/test_fuzz_regressions.cpp):
// each returns "" when the input is handled as promised (a sound result, or a RoundingError), else the
// finding. Memory errors and undefined behaviour are the sanitizers' to report.
#pragma once
#include <Standard_Failure.hxx>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "fuzz_input.h"
#include "meshround/chain.h"
#include "meshround/mesh.h"
#include "meshround/round.h"
#include "meshround/sharpen.h"
#include "sound.h"

namespace meshround::fuzz {

// MESHROUND_FUZZ_DUMP=prefix: the case's input and result written as prefix_in.obj / prefix_out.obj.
inline void dump_obj(const Points& V, const Triangles& F, const char* suffix) {
  const char* prefix = std::getenv("MESHROUND_FUZZ_DUMP");
  if (!prefix) return;
  std::FILE* out = std::fopen((std::string(prefix) + suffix).c_str(), "w");
  if (!out) return;
  for (int v = 0; v < V.rows(); ++v) std::fprintf(out, "v %.17g %.17g %.17g\n", V(v, 0), V(v, 1), V(v, 2));
  for (int f = 0; f < F.rows(); ++f) std::fprintf(out, "f %d %d %d\n", F(f, 0) + 1, F(f, 1) + 1, F(f, 2) + 1);
  std::fclose(out);
}

inline bool verbose() {
  static const bool v = std::getenv("MESHROUND_FUZZ_VERBOSE") != nullptr;
  return v;
}

// MESHROUND_FUZZ_MAX_NEW_FACETS=N: every case runs with the work budget RoundOptions::max_new_facets
// at most N (0 or unset: the decoder's own, the engine's default), so that a case that would make more
// is refused (work_limit) before it is made: a long run's executions per second are then set by the
// cases' common size, not by their slow tail. fuzz_round and fuzz_arrays' rounding branch both honour it.
inline long fuzz_work_budget() {
  static const long budget = [] {
    const char* text = std::getenv("MESHROUND_FUZZ_MAX_NEW_FACETS");
    return text ? std::max(0L, std::atol(text)) : 0L;
  }();
  return budget;
}

// A case's body (its finding, or ""), where a RoundingError is a refusal for `refused` to judge and any other
// exception that escapes is a finding.
template <class Body, class Refused>
std::string guarded(Body&& body, Refused&& refused) {
  try {
    return body();
  } catch (const RoundingError& e) {
    return refused(e);
  } catch (const Standard_Failure& e) {
    return std::string("Standard_Failure escaped: ") + e.DynamicType()->Name() + ": " + e.GetMessageString();
  } catch (const std::exception& e) {
    return std::string("std::exception escaped: ") + e.what();
  } catch (...) {
    return "unknown exception escaped";
  }
}

// A generated mesh and options (fuzz_input.h) through round_edges; a success must be sound (sound.h)
// and leave the input arrays as they were.
inline std::string round_case(const std::uint8_t* data, std::size_t size) {
  FuzzCase c = decode_case(data, size);
  if (fuzz_work_budget() > 0) c.options.max_new_facets = std::min(c.options.max_new_facets, fuzz_work_budget());
  if (c.F.rows() > 6000) return "";  // keep executions fast (the decoder's bounds keep it under this)
  const Points V0 = c.V;
  const Triangles F0 = c.F;
  if (verbose())
    std::fprintf(stderr, "mesh %ld v %ld f, element %g, seeds %zu, r %g (law %zu), tol %g, angle %g, reach %g\n", long(c.V.rows()),
                 long(c.F.rows()), c.element, c.seeds.size(), c.options.radius, c.options.radius_law.size(), c.options.tolerance,
                 c.options.feature_angle_deg, c.options.reach);
  if (verbose())
    for (const Vec3& p : c.seeds) std::fprintf(stderr, "seed %.17g %.17g %.17g\n", p.x(), p.y(), p.z());
  return guarded([&]() -> std::string {
    dump_obj(c.V, c.F, "_in.obj");
    const RoundResult res = round_edges(c.V, c.F, c.seeds, c.options);
    dump_obj(res.vertices, res.triangles, "_out.obj");
    if (!(c.V.array() == V0.array()).all() && !(c.V.hasNaN() && V0.hasNaN())) return "the input vertices changed";
    if (!(c.F.array() == F0.array()).all()) return "the input facets changed";
    SoundnessInput s{c.V, c.F, res.vertices, res.triangles, {}, 0};
    for (const RoundedChain& ch : res.chains)
      if (!ch.chain.empty()) s.chain_ends.push_back(ch.chain.front()), s.chain_ends.push_back(ch.chain.back());
    double rmax = c.options.radius;
    for (const RadiusControl& rc : c.options.radius_law) rmax = std::max(rmax, rc.radius);
    s.end_allowance = 1.5 * c.options.reach * rmax;
    const auto checking = std::chrono::steady_clock::now();
    const std::string bad = check_sound(s);
    if (verbose()) {
      const std::chrono::duration<double> checked = std::chrono::steady_clock::now() - checking;
      std::fprintf(stderr, "rounded: %ld facets, %s (checked in %.3f s); seconds:", long(res.triangles.rows()),
                   bad.empty() ? "sound" : bad.c_str(), checked.count());
      for (const auto& [pass, t] : res.report.seconds) std::fprintf(stderr, " %s %.3f", pass.c_str(), t);
      std::fprintf(stderr, "\n");
    }
    return bad.empty() ? "" : "unsound result: " + bad;
  }, [&](const RoundingError& e) -> std::string {
    if (verbose()) std::fprintf(stderr, "refused (%s): %s\n", error_code_name(e.code), e.what());
    if (!(c.V.array() == V0.array()).all() && !(c.V.hasNaN() && V0.hasNaN())) return "the input vertices changed";
    return "";
  });
}

// round_case's call, then, where it rounds, change_radius on its result through the same seeds, at a radius
// the input's last byte picks (0: sharpen; or 0.5, 0.8, 1, 1.25 or 2 times the first): a success must be sound
// against the rounded mesh and leave it as it was, a failure a RoundingError.
inline std::string reround_case(const std::uint8_t* data, std::size_t size) {
  FuzzCase c = decode_case(data, size);
  if (fuzz_work_budget() > 0) c.options.max_new_facets = std::min(c.options.max_new_facets, fuzz_work_budget());
  if (c.F.rows() > 6000) return "";
  static constexpr double kFactor[6] = {0, 0.5, 0.8, 1, 1.25, 2};
  const double factor = kFactor[size ? data[size - 1] % 6 : 0];
  return guarded([&]() -> std::string {
    RoundResult first;
    const auto start = std::chrono::steady_clock::now();
    auto seconds = [&start] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
    try {
      first = round_edges(c.V, c.F, c.seeds, c.options);
    } catch (const RoundingError&) {
      return "";  // (round_case's to judge)
    }
    const Points V1 = first.vertices;
    const Triangles F1 = first.triangles;
    RoundOptions again = c.options;
    again.radius = factor * c.options.radius, again.radius_law.clear();
    if (verbose()) std::fprintf(stderr, "rounded (%ld facets, %.2f s); change_radius to %g\n", long(F1.rows()), seconds(), again.radius);
    const ChangeRadiusResult res = change_radius(first.vertices, first.triangles, c.seeds, again);
    dump_obj(V1, F1, "_in.obj"), dump_obj(res.round.vertices, res.round.triangles, "_out.obj");
    if (!(first.vertices.array() == V1.array()).all() || !(first.triangles.array() == F1.array()).all()) return "the input changed";
    SoundnessInput s{V1, F1, res.round.vertices, res.round.triangles, {}, 0};
    double r = again.radius;
    for (const StripReport& strip : res.strips) {
      s.chain_ends.push_back(strip.corner[0]), s.chain_ends.push_back(strip.corner[1]);
      r = std::max(r, strip.found_radius);
    }
    for (const RoundedChain& ch : res.round.chains)
      if (!ch.chain.empty()) s.chain_ends.push_back(ch.chain.front()), s.chain_ends.push_back(ch.chain.back());
    s.end_allowance = 1.5 * c.options.reach * r;
    const double made = seconds();
    const std::string bad = check_sound(s);
    if (verbose())
      std::fprintf(stderr, "made again: %ld facets at %.2f s, %s (checked at %.2f s)\n", long(res.round.triangles.rows()), made,
                   bad.empty() ? "sound" : bad.c_str(), seconds());
    if (verbose()) {
      std::fprintf(stderr, "sharpen %.3f s; rounding seconds:", res.seconds_sharpen);
      for (const auto& [pass, t] : res.round.report.seconds) std::fprintf(stderr, " %s %.3f", pass.c_str(), t);
      std::fprintf(stderr, "\n");
    }
    return bad.empty() ? "" : "unsound result of change_radius: " + bad;
  }, [](const RoundingError& e) -> std::string {
    if (verbose()) std::fprintf(stderr, "change_radius refused (%s): %s\n", error_code_name(e.code), e.what());
    return "";
  });
}

inline double coordinate(ByteReader& in) {
  switch (in.below(8)) {
    case 0: return in.raw_double();
    case 1: return double(int(in.below(5)) - 2);
    default: {  // a small lattice: shared edges, folds (reads in sequence, see ByteReader)
      const double whole = in.below(5), part = in.u8() / 256.0;
      return whole + part * (in.chance(128) ? 1 : 1e-9);
    }
  }
}

// Raw (V, F) -- arbitrary indices, NaN / inf / huge coordinates -- into MeshTopology and its queries,
// find_chains, collect_base_meshes and, now and then, round_edges.
inline std::string arrays_case(const std::uint8_t* data, std::size_t size) {
  ByteReader in(data, size);
  const int n = in.below(40), m = in.below(60);
  Points V(n, 3);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) V(i, k) = coordinate(in);
  Triangles F(m, 3);
  for (int f = 0; f < m; ++f)
    for (int k = 0; k < 3; ++k) F(f, k) = in.chance(8) ? int(in.u32()) : (n > 0 ? in.below(n) : 0);
  std::vector<Vec3> seeds;
  for (int k = in.range(0, 2); k > 0; --k) {
    const double x = coordinate(in), y = coordinate(in), z = coordinate(in);
    seeds.push_back(Vec3(x, y, z));
  }
  const double angle = in.chance(200) ? 30 : (in.chance(128) ? in.uniform(0, 180) : in.raw_double());
  const double search = in.chance(128) ? 0 : (in.chance(200) ? in.uniform(0, 10) : in.raw_double());
  const bool round = in.chance(48);
  return guarded([&]() -> std::string {
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
        if (fuzz_work_budget() > 0) o.max_new_facets = std::min(o.max_new_facets, fuzz_work_budget());
        const Points V0 = V;
        const Triangles F0 = F;
        (void)round_edges(V, F, seeds, o);
        if (!(F.array() == F0.array()).all()) return "the input facets changed";
      }
    }
    return "";
  }, [](const RoundingError&) { return std::string(); });
}

}  // namespace meshround::fuzz
