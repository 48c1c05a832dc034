// Private to the sharpen pass (sharpen.cpp, sharpen_line.cpp): the fold of a strip's vertices onto the two
// sides, and the clean-up of the rebuilt edge once they are folded.
#pragma once
#include <cstdint>
#include <unordered_map>

#include "meshround/mesh_edit.h"
#include "strip.h"

namespace meshround::sharpen_detail {

// Where a strip vertex goes: its share t of the arc (0 at border A, 1 at border B) and its image on the
// corner's two sides (plane A for t < 1/2, plane B for t > 1/2, the corner line at 1/2).
struct Fold {
  std::unordered_map<int, double> t;
  std::unordered_map<std::uint64_t, int> split;  // strip edge across the corner line -> its point there
  double setback = 0;                            // largest distance moved (the corner from the arc)
};

// Points on the rebuilt edge much closer than its usual spacing merged, and a mitred strip's corners made
// one point each; returns how many points went.
int merge_close_points(const MeshTopology& mesh, const RoundStrip& strip, double r, MeshEdit& edit, const Fold& fold);

// A mitred strip's folded facets without area dropped (their neighbours split, or two corners on one point
// made one); returns how many.
int drop_flat_facets(const MeshTopology& mesh, const RoundStrip& strip, MeshEdit& edit);

// A side's facet beside the old round that folds against it (a mesher's sliver along the contact line on a
// curved wall: its three corners on the wall, but its plane tilted by the wall's sag across its short height)
// makes a kink on the rebuilt side where there was the round's turn; the edge between the two is flipped
// when that takes off a quarter of the kink or more without a worse angle (round_edges reads a kink of 30 deg as a sharp edge and
// its ball as reaching past it). Returns how many edges were flipped.
int unkink_borders(const MeshTopology& mesh, const RoundStrip& strip, MeshEdit& edit);

}  // namespace meshround::sharpen_detail
