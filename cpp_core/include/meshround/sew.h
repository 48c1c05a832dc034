// Paper §5.3: the round and the trimmed mesh become one conforming mesh.
//
// The round already shares its boundary vertices with the trim lines, so sewing is: orient the round
// like its neighbours, close the gaps left at capped chain ends (planar end-face pieces between the end
// profile and the trimmed end face), and write the compact output arrays.
#pragma once
#include "meshround/mesh_delta.h"
#include "meshround/mesh_edit.h"

namespace meshround {

struct SewStats {
  int gap_facets = 0;     // facets added to close gaps at chain ends
  int open_gaps = 0;      // gaps left open (they reach the mesh boundary)
  bool round_flipped = false;
};

// `round_begin`: index in edit.added of the round's first facet (the rest up to round_end are the round).
// `fill` refines the triangulation of the gaps (end caps), e.g. inner points near the chain only.
SewStats sew_round(MeshEdit& edit, size_t round_begin, size_t round_end, const Refinement& fill = {});

// The edited mesh as compact arrays, in apply_delta's order (mesh_delta.h): unused vertices dropped, the
// input's kept vertices keep their order and values. `origin` (optional): where each came from.
void write_mesh(const MeshEdit& edit, Points& V, Triangles& F, StepOrigin* origin = nullptr);

}  // namespace meshround
