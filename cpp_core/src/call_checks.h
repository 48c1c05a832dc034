// The checks every engine call makes before it works (private to cpp_core): the options, the precision
// the mesh's coordinates carry, and the seeds.
#pragma once
#include <vector>

#include "meshround/options.h"
#include "meshround/types.h"

namespace meshround {

// The options (validate_options), the radius and tolerance against the mesh's precision
// (radius_too_small, naming the smallest value that works), and at least one seed.
void check_call(const Points& V, const std::vector<Vec3>& seeds, const RoundOptions& opt);

}  // namespace meshround
