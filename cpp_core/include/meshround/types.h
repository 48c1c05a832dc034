// Shared array types and the one exception the engine throws.
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <stdexcept>
#include <string>

namespace meshround {

using Vec3 = Eigen::Vector3d;
using Points = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;    // vertices, (n, 3)
using Triangles = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;    // facets, (m, 3), 0-based

// Why a call was refused: one of a documented set (README, "Errors"), so that scripts can act on it.
enum class ErrorCode {
  InvalidInput,        // invalid_input: an argument or the mesh's arrays are malformed or out of range
  NoSharpEdge,         // no_sharp_edge: no sharp edge near a seed
  NonManifoldInput,    // non_manifold_input: the mesh near the chain is open, non-manifold or degenerate
  RadiusTooLarge,      // radius_too_large: no ball of that radius fits between the faces
  RadiusTooSmall,      // radius_too_small: the radius or tolerance is below what the mesh can carry
  BeyondReach,         // beyond_reach: the ball touches the mesh beyond the reach (raise the reach factor)
  CornerNotBlendable,  // corner_not_blendable: chains meet at a vertex whose corner cannot be made
  SurfaceFailed,       // surface_failed: the rounding surface could not be built through the profiles
  ResultInvalid,       // result_invalid: the result failed the output check; nothing is returned
  Cancelled,           // cancelled: the caller asked the run to stop
  WorkLimit,           // work_limit: the rounding would make more facets than the work budget allows
  NotARound,           // not_a_round: the strip a seed picks is not a round between two flat sides (change_radius)
};
// The code's name as scripts see it ("radius_too_large").
const char* error_code_name(ErrorCode code);

// Every failure the user can cause (bad input, radius too large, ...) is a RoundingError whose message
// names the cause and, where it has one, the place. The input is never modified when it is thrown.
struct RoundingError : std::runtime_error {
  RoundingError(ErrorCode c, const std::string& what) : std::runtime_error(what), code(c) {}
  ErrorCode code;
};

std::string format_point(const Vec3& p);  // "(x, y, z)" for messages
std::string format_number(double x);      // 6 significant digits, for messages

}  // namespace meshround
