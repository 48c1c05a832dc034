// Private to the strip recognition (strip_curved.cpp): the corner line of a round whose side B curves along
// it -- its stations' frames put in order along the line, a loop's closing checked, the stations' tilts
// smoothed, and the C1 curve through their corners that each strip vertex takes its section's corner from.
#pragma once
#include <utility>
#include <vector>

#include "strip_facets.h"

namespace meshround::strip_detail {

// The point x with n0 . x = rhs(0), n1 . x = rhs(1), axis . x = rhs(2): a frame's corner (its two side planes
// and its section), or, with the sides' signs, the direction of its ball's centre.
Vec3 frame_solve(const Vec3& n0, const Vec3& n1, const Vec3& axis, const Vec3& rhs);

// The corner line through the stations' corner points as a C1 curve (cubic Hermite on each span, the
// tangents by differences over the neighbouring spans), by arc length s: a vertex between two stations
// takes its section's corner on it, not on its station's tangent (h^2 / 8R off at mid-span).
struct CornerCurve {
  const std::vector<StripFrame>& station;
  std::vector<double> s;  // each station's arc length; a loop's closing span ends at `loop`
  bool closed;
  double loop = 0;

  CornerCurve(const std::vector<StripFrame>& st, bool is_closed) : station(st), s(st.size(), 0.0), closed(is_closed) {
    for (size_t i = 1; i < st.size(); ++i) s[i] = s[i - 1] + (st[i].corner - st[i - 1].corner).norm();
    loop = closed ? s.back() + (st.front().corner - st.back().corner).norm() : s.back();
  }
  size_t count() const { return station.size(); }
  const Vec3& P(long i) const { const long n = long(count()); return station[size_t(((i % n) + n) % n)].corner; }
  double S(long i) const {  // arc length of station i, unwrapped around a loop
    const long n = long(count());
    const long w = ((i % n) + n) % n;
    return s[size_t(w)] + double((i - w) / n) * loop;
  }
  Vec3 tangent(long i) const {
    const long n = long(count());
    if (!closed && i == 0) return (P(1) - P(0)) / std::max(S(1) - S(0), 1e-300);
    if (!closed && i == n - 1) return (P(n - 1) - P(n - 2)) / std::max(S(n - 1) - S(n - 2), 1e-300);
    return (P(i + 1) - P(i - 1)) / std::max(S(i + 1) - S(i - 1), 1e-300);
  }
  // The point at arc length u and its derivative (unit-ish); an open line goes on straight past its ends.
  Vec3 at(double u, Vec3* d) const {
    const long n = long(count());
    if (n < 3) {
      *d = (P(n - 1) - P(0)).normalized();
      return P(0) + *d * (u - S(0));
    }
    if (!closed && (u <= S(0) || u >= S(n - 1))) {
      const long e = u <= S(0) ? 0 : n - 1;
      *d = tangent(e);
      return P(e) + *d * (u - S(e));
    }
    if (closed) u -= std::floor(u / loop) * loop;
    long j = long(std::upper_bound(s.begin(), s.end(), u) - s.begin()) - 1;
    j = std::clamp(j, 0L, closed ? n - 1 : n - 2);
    const double h = std::max(S(j + 1) - S(j), 1e-300), x = (u - S(j)) / h;
    const Vec3 m0 = h * tangent(j), m1 = h * tangent(j + 1);
    *d = ((6 * x * x - 6 * x) * P(j) + (3 * x * x - 4 * x + 1) * m0 + (-6 * x * x + 6 * x) * P(j + 1) + (3 * x * x - 2 * x) * m1) / h;
    return (2 * x * x * x - 3 * x * x + 1) * P(j) + (x * x * x - 2 * x * x + x) * m0 + (-2 * x * x * x + 3 * x * x) * P(j + 1) +
           (x * x * x - x * x) * m1;
  }
};

// The stations of a round all around a loop, in order: each next one at most kLoopGap times the median
// spacing away (else the nearest-next ordering skipped one and came back for it; not asked of stations
// `walked` in order along the border, order_around), and the corner line turning by kLoopTurnDeg at
// most between any two in a row, the last and the first included.
void close_loop(const std::vector<StripFrame>& station, const Vec3& where, bool walked);

// The stations' corner points scatter about the true corner line: each station's tangent plane of side B is
// fitted to a few facets of a tessellated wall, and a tilt of a degree moves its corner by the round's
// height x 0.017 (0.1 mm on a 3 mm round, ten times the wall's chordal error). The tilt (side B's angle to
// plane A in the station's section) changes slowly along a wall, while the corner line itself may bend
// sharply (a straight run into an arc): each station's tilt is put on a line fitted to the tilts of the
// kSmoothStations stations each side (the window's constants in strip_line.cpp) (those far off the window's median left out), its plane B turned to it
// about the axis through its border vertex's foot on it, and its corner solved again (a station moved by over a
// fifth of its round's width is kept as measured: not a scatter). `border`: each station's border B vertex.
void smooth_tilts(std::vector<StripFrame>& station, const std::vector<Vec3>& border, bool closed);

// The stations in order along the corner line: from the one farthest from their middle, each next the
// nearest (`vertex`, each station's border vertex, kept alongside).
void order_along(std::vector<StripFrame>& station, std::vector<int>& vertex);

// The stations of a round all around a loop in the order their border vertices come along border B (its
// edges `border_edges`, each (strip facet, edge)): right however unevenly they are spaced (a CAD mesh's
// wall: one long facet along a straight stretch between arcs of short ones, where the nearest next station
// lies on across the arc). False (nothing changed) where border B is not one loop through every station.
bool order_around(const MeshTopology& mesh, const std::vector<std::pair<int, int>>& border_edges, std::vector<StripFrame>& station,
                  std::vector<int>& vertex);

}  // namespace meshround::strip_detail
