// One chain rounded on meshes of about 10k, 100k and 1M facets (a box, its top edge, r = 5).
// The adjacency build is O(n); everything after it should scale with the band, not the mesh.
// Run: build/bench/meshround_bench
// Peak memory: run one size per process, e.g. --benchmark_filter=BM_RoundOneChain/1000000; the counters
// rss_mesh_mb (after the input is built) and peak_rss_mb (the process's peak) then belong to that size.
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <cmath>
#include <map>

#include "meshround/mesh.h"
#include "meshround/mesh_edit.h"
#include "meshround/round.h"

using namespace meshround;

namespace {

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // Linux: kilobytes
}

// A closed box 100 x 60 x 40 of right triangles with about `facets` facets.
std::pair<Points, Triangles> box_mesh(int facets) {
  const double area = 2 * (100 * 60 + 100 * 40 + 60 * 40);
  const double h = std::sqrt(2 * area / facets);
  std::vector<Vec3> pts;
  std::vector<std::array<int, 3>> tris;
  std::map<std::array<long, 3>, int> index;
  auto vid = [&](const Vec3& p) {
    std::array<long, 3> k{std::lround(p.x() * 1e6), std::lround(p.y() * 1e6), std::lround(p.z() * 1e6)};
    auto [it, fresh] = index.emplace(k, int(pts.size()));
    if (fresh) pts.push_back(p);
    return it->second;
  };
  const Vec3 size(100, 60, 40);
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int a = (axis + 1) % 3, b = (axis + 2) % 3;
      const int na = std::max(1, int(std::round(size[a] / h))), nb = std::max(1, int(std::round(size[b] / h)));
      for (int i = 0; i < na; ++i)
        for (int j = 0; j < nb; ++j) {
          Vec3 p[4];
          for (int c = 0; c < 4; ++c) {
            p[c][axis] = side * size[axis];
            p[c][a] = size[a] * (i + (c == 1 || c == 2)) / na;
            p[c][b] = size[b] * (j + (c >= 2)) / nb;
          }
          int q[4] = {vid(p[0]), vid(p[1]), vid(p[2]), vid(p[3])};
          if (side) std::swap(q[1], q[3]);
          tris.push_back({q[0], q[1], q[2]}), tris.push_back({q[0], q[2], q[3]});
        }
    }
  Points V(Eigen::Index(pts.size()), 3);
  for (size_t i = 0; i < pts.size(); ++i) V.row(Eigen::Index(i)) = pts[i].transpose();
  Triangles F(Eigen::Index(tris.size()), 3);
  for (size_t i = 0; i < tris.size(); ++i) F.row(Eigen::Index(i)) << tris[i][0], tris[i][1], tris[i][2];
  return {V, F};
}

void BM_RoundOneChain(benchmark::State& state) {
  const auto [V, F] = box_mesh(int(state.range(0)));
  const double rss_mesh = peak_rss_mb();
  RoundOptions opt;
  opt.radius = 5;
  RoundReport report;
  for (auto _ : state) {
    RoundResult r = round_edges(V, F, {Vec3(37, 60, 40)}, opt);
    benchmark::DoNotOptimize(r.triangles.data());
    report = r.report;
  }
  state.counters["facets"] = double(F.rows());
  // Facets under 10 degrees make the engine round the chain again at wider reaches (round.h): a
  // benchmark that has any measures that probe too.
  state.counters["thin_facets"] = report.thin_facets;
  state.counters["input_arrays_mb"] = double(V.size() * sizeof(double) + F.size() * sizeof(int)) / (1 << 20);
  state.counters["rss_mesh_mb"] = rss_mesh;
  state.counters["peak_rss_mb"] = peak_rss_mb();
}

// The O(n) part alone: vertex-facet adjacency of the whole mesh, built once per call.
void BM_AdjacencyBuild(benchmark::State& state) {
  const auto [V, F] = box_mesh(int(state.range(0)));
  for (auto _ : state) {
    MeshTopology topology(V, F);
    benchmark::DoNotOptimize(&topology);
  }
  state.counters["facets"] = double(F.rows());
}

// A trim polygon as a band through a large facet hands it over: a 100 x 50 triangle whose long side is the
// trim line, in `sides` points, with inner points admitted within 0.5 of that line. The refinement's cost
// per point should not grow with the polygon (it was quadratic: about 140 s for a 12,000-point line).
void BM_RefineTrimPolygon(benchmark::State& state) {
  const int sides = int(state.range(0));
  Points V(3, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  Triangles F(1, 3);
  F << 0, 1, 2;
  const MeshTopology input(V, F);
  Refinement refine{20.0, [](const Vec3& p) { return p.y() < 0.5; }, 0.0};
  size_t made = 0;
  for (auto _ : state) {
    MeshEdit edit(input);
    std::vector<int> polygon;
    for (int i = 0; i < sides; ++i) polygon.push_back(edit.add_point(Vec3(100.0 * i / sides, 0, 0)));
    polygon.push_back(edit.add_point(Vec3(100, 0, 0)));
    polygon.push_back(edit.add_point(Vec3(50, 50, 0)));
    std::vector<std::array<int, 3>> tris;
    triangulate_polygon(edit, polygon, Vec3::UnitZ(), tris, refine);
    made = tris.size();
    benchmark::DoNotOptimize(tris.data());
  }
  state.counters["triangles"] = double(made);
}

}  // namespace

BENCHMARK(BM_RefineTrimPolygon)->Arg(500)->Arg(1000)->Arg(4000)->Arg(16000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AdjacencyBuild)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->MinTime(0.5);
BENCHMARK(BM_RoundOneChain)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->MinTime(0.5);
BENCHMARK_MAIN();
