// Networks of picked chains (round_edges): where chains of one call meet at a vertex, and how each
// round ends there -- a mitre between two rounds, or the plane across the chain through the ball of a
// sphere corner (sphere_corner.h) between three or more.
#pragma once
#include <array>
#include <functional>
#include <utility>
#include <vector>

#include "meshround/chain.h"
#include "meshround/options.h"
#include "meshround/round.h"
#include "meshround/spine.h"
#include "sphere_corner.h"

namespace meshround {

// Where a chain meets another picked chain at a corner (round_edges): the plane its round stops at there
// (at a mitre, through the corner vertex, bisecting the two chains; at a sphere corner, through the
// corner ball's centre and its feet on the chain's faces), and whether the other round is made already
// (then this round's end column is that round's, see SharedEnds); and the vertices of the rounds made before.
struct CornerEnd {
  Vec3 point, normal;
  bool other_made = false;
  Vec3 plane_point = point;  // the plane's point: the vertex for a mitre, the ball's centre at a sphere corner
  bool sphere = false;       // one of three or more rounds at the vertex (sphere_corner.h)
  std::array<Vec3, 2> feet{};  // at a sphere corner: the ball's feet on the chain's two faces, where its round's end profile ends
};
struct NetworkPart {
  std::vector<CornerEnd> corners;
  std::vector<Vec3> earlier_round_points;
  const std::vector<SharpChain>* chains = nullptr;  // all chains of the call (on the input), when several
  const std::vector<ExactRound>* earlier_rounds = nullptr;  // rounds of a first stage (stages.h), if any
  // Rolled corners with a tight ring (RolledCorner::tight): their vertices, near which the profile stations are
  // resolved finer (round.cpp sample_profiles).
  const std::vector<Vec3>* tight_rings = nullptr;
};

// The corner at a chain end (its end vertex is the corner's point), or null.
const CornerEnd* corner_at(const NetworkPart& net, const Vec3& end_point);

// Where three picked chains end at one vertex with convex and concave edges mixed -- a pocket's rim
// corner: two convex rim edges and the concave wall edge between them -- or with one convexity and radii that
// differ -- a box's vertical edge of 8 between top edges of 5; the largest radius, or one of two that share it --, the
// rolling ball makes the odd chain's round first, and the other two then as one round rolling
// on around its end (a torus where the faces are square, as in OCCT's fillet). round_edges makes the odd
// chains in a first call and traces the others anew on its result, where the sharp edge runs on around
// the odd round's end (stages.h).
struct RolledCorner {
  Vec3 vertex;
  size_t odd = 0;                    // the chain of the other convexity, or of the largest radius: rounded first
  std::array<size_t, 2> pair{0, 0};  // rounded after it, as one round
  bool odd_convex = false, pair_convex = false;
  // The pair's radii at the vertex where they differ, else {0, 0}: their round goes from one to the other
  // round the odd round's end (round_in_stages), as OCCT's fillet lets its ball's radius evolve there.
  std::array<double, 2> pair_radius{0.0, 0.0};
  // The ring the pair's balls' centres run on round the odd round's axis is under kRolledRingShare of their
  // radius (a radius R between r and 1.125 r; none at one end where R is the pair's larger radius, 8 / 8 / 5).
  bool tight = false;
};

// Each chain's stage: 0 made first, 1 made on stage 0's result (RolledCorner, one entry per such vertex
// into `rolled`). Chains meeting at a mitre or a sphere corner share a stage. Refuses
// (corner_not_blendable, naming the vertices) a chain that would have to be made both before and after
// its neighbours, and a variable radius along the chain made first at a rolled corner (each chain may
// have its own radius: the one made first is carried into the second stage as an exact round of it).
std::vector<int> plan_stages(const MeshTopology& input, const std::vector<SharpChain>& chains, const std::vector<Vec3>& picked,
                             const RoundOptions& opt, std::vector<RolledCorner>* rolled);

// Each chain's corners with the others (chains traced on `input`, `picked` their seeds), and the sphere
// corners with a chain that ends at each. Refuses (corner_not_blendable, naming the vertex) what is not
// made yet.
std::vector<NetworkPart> find_corners(const MeshTopology& input, const std::vector<SharpChain>& chains, const std::vector<Vec3>& picked,
                                      const RoundOptions& opt, std::vector<std::pair<SphereCorner, size_t>>* spheres);

// The chains the seeds select on `input`, traced as round_edges takes them (search radius reach x r), one per
// distinct chain (a seed on a chain picked already adds nothing), each with the seed that picked it.
struct PickedChains {
  std::vector<SharpChain> chains;
  std::vector<Vec3> picked;
};
PickedChains pick_chains(const MeshTopology& input, const std::vector<Vec3>& seeds, const RoundOptions& opt);

// The corners of the picked chains and each one's blend, by the rules round_edges uses (plan_stages, then
// find_corners on the chains made first), into `plan` (round.h); a corner refusal is kept in the plan.
void plan_corners(const MeshTopology& input, const PickedChains& picked, const RoundOptions& opt, NetworkPlan& plan);

// Each chain's options: a radius law keeps the control points nearest to that chain (a point at a corner,
// as near to several chains, belongs to each of them); a chain without a control point is an error, as is
// a point far from every chain.
std::vector<RoundOptions> options_per_chain(const RoundOptions& opt, const std::vector<SharpChain>& chains,
                                            const std::vector<Vec3>& picked);

// Where a network's passes may place points: within the reach (reach x its largest radius) of any of its chains.
std::function<bool(const Vec3&)> within_reach_of(const std::vector<SharpChain>& chains, const std::vector<RoundOptions>& options);

// One radius along the whole chain (a chain's own options): no law, or a law whose control points all give
// the same radius; and that radius (the first control point's, for a law).
bool constant_radius(const RoundOptions& own);
double one_radius(const RoundOptions& own);

}  // namespace meshround
