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

// Every failure the user can cause (bad input, radius too large, ...) is a RoundingError whose message
// names the cause and, where it has one, the place. The input is never modified when it is thrown.
struct RoundingError : std::runtime_error {
  explicit RoundingError(const std::string& what) : std::runtime_error(what) {}
};

std::string format_point(const Vec3& p);  // "(x, y, z)" for messages
std::string format_number(double x);      // 6 significant digits, for messages

}  // namespace meshround
