// _meshround_core: the engine for Python (numpy in, numpy + BRep text out). See CONTRACT.md.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/eval.h>
#include <pybind11/stl.h>

#include <Standard_Failure.hxx>

#include <atomic>

#include "meshround/max_radius.h"
#include "meshround/round.h"
#include "meshround/sharpen.h"

namespace py = pybind11;
using namespace meshround;

namespace {

// A request to stop a run, from any thread: cancel() sets the flag the engine polls (no GIL is needed to
// poll it: the engine reads the atomic directly while the GIL is released).
struct CancelToken {
  std::atomic<bool> flag{false};
};

Points to_points(const py::array& a, const char* what) {
  auto arr = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!arr || arr.ndim() != 2 || (arr.shape(1) != 3 && arr.shape(0) > 0))
    throw RoundingError(ErrorCode::InvalidInput, std::string(what) + " must be an (n, 3) array of numbers");
  Points P(arr.shape(0), 3);
  std::copy(arr.data(), arr.data() + arr.size(), P.data());
  return P;
}

Triangles to_triangles(const py::array& a) {
  auto arr = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!arr || arr.ndim() != 2 || (arr.shape(1) != 3 && arr.shape(0) > 0))
    throw RoundingError(ErrorCode::InvalidInput, "triangles must be an (m, 3) array of vertex indices");
  Triangles F(arr.shape(0), 3);
  const long long* d = arr.data();
  for (py::ssize_t i = 0; i < arr.size(); ++i) {
    if (d[i] < 0 || d[i] > 0x7fffffff) throw RoundingError(ErrorCode::InvalidInput, "a triangle has a negative or too large vertex index");
    F.data()[i] = int(d[i]);
  }
  return F;
}

std::vector<Vec3> to_vecs(const Points& P) {
  std::vector<Vec3> out;
  for (int i = 0; i < P.rows(); ++i) out.push_back(P.row(i).transpose());
  return out;
}

py::array_t<double> polyline(const std::vector<Vec3>& pts) {
  py::array_t<double> a({py::ssize_t(pts.size()), py::ssize_t(3)});
  auto m = a.mutable_unchecked<2>();
  for (size_t i = 0; i < pts.size(); ++i)
    for (int k = 0; k < 3; ++k) m(i, k) = pts[i][k];
  return a;
}

// Converts OCCT's own exceptions into RoundingError so Python never sees a crash.
template <class F>
auto guarded(F&& f) {
  try {
    return f();
  } catch (const Standard_Failure& e) {
    throw RoundingError(ErrorCode::SurfaceFailed, std::string("geometry kernel failure: ") + e.GetMessageString());
  }
}

// The band element controls from a dict {"max_element_angle": deg, "element_length": mm,
// "max_aspect_ratio": x} (any may be missing; None: all off).
void set_band_controls(RoundOptions& opt, const py::object& band) {
  if (band.is_none()) return;
  if (!py::isinstance<py::dict>(band)) throw RoundingError(ErrorCode::InvalidInput, "band must be a dict of element controls or None");
  for (auto [key, value] : band.cast<py::dict>()) {
    const std::string name = py::str(key);
    double* field = name == "max_element_angle"  ? &opt.max_element_angle_deg
                    : name == "element_length"   ? &opt.element_length
                    : name == "max_aspect_ratio" ? &opt.max_aspect_ratio
                                                 : nullptr;
    if (!field) throw RoundingError(ErrorCode::InvalidInput, "unknown band element control '" + name + "'");
    if (!value.is_none()) *field = value.cast<double>();
  }
}

RoundOptions to_options(double radius, double tolerance, double feature_angle, double reach, const py::object& radius_law,
                        const py::object& band) {
  RoundOptions opt;
  set_band_controls(opt, band);
  opt.radius = radius;
  opt.tolerance = tolerance;
  opt.feature_angle_deg = feature_angle;
  opt.reach = reach;
  if (!radius_law.is_none()) {
    auto law = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(radius_law);
    if (!law || law.ndim() != 2 || law.shape(1) != 4) throw RoundingError(ErrorCode::InvalidInput, "radius_law must be a (p, 4) array of [x, y, z, r]");
    for (py::ssize_t i = 0; i < law.shape(0); ++i)
      opt.radius_law.push_back({Vec3(law.at(i, 0), law.at(i, 1), law.at(i, 2)), law.at(i, 3)});
  }
  return opt;
}

void set_budget_and_cancel(RoundOptions& opt, long max_new_facets, const py::object& cancel);
py::dict result_dict(const RoundResult& res, bool arrays, bool with_delta);

// A rounding call's arguments, converted and checked (round_edges and change_radius take the same ones).
struct Call {
  Points V;
  Triangles F;
  std::vector<Vec3> seeds;
  RoundOptions opt;
};

Call to_call(const py::array& vertices, const py::array& triangles, const py::array& seeds, double radius, double tolerance,
             double feature_angle, double reach, const py::object& radius_law, long max_new_facets, const py::object& cancel,
             const py::object& band) {
  Call c{to_points(vertices, "vertices"), to_triangles(triangles), to_vecs(to_points(seeds, "seeds")),
         to_options(radius, tolerance, feature_angle, reach, radius_law, band)};
  set_budget_and_cancel(c.opt, max_new_facets, cancel);
  return c;
}

// ---------------------------------------------------------------------------------------------- mesh deltas
template <class T>
py::array_t<T> vector_array(const std::vector<T>& v) {
  py::array_t<T> a(py::ssize_t(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

py::array_t<double> point_rows(const std::vector<Vec3>& pts) { return polyline(pts); }

py::array_t<int> facet_rows(const std::vector<std::array<int, 3>>& facets) {
  py::array_t<int> a({py::ssize_t(facets.size()), py::ssize_t(3)});
  if (!facets.empty()) std::copy(facets.front().data(), facets.front().data() + 3 * facets.size(), a.mutable_data());
  return a;
}

py::dict delta_dict(const MeshDelta& d) {
  py::dict out;
  out["input_vertices"] = d.input_vertices, out["input_facets"] = d.input_facets;
  out["removed"] = vector_array(d.removed), out["freed"] = vector_array(d.freed);
  out["moved"] = vector_array(d.moved), out["moved_to"] = point_rows(d.moved_to);
  out["new_points"] = point_rows(d.new_points), out["added"] = facet_rows(d.added);
  return out;
}

std::vector<int> int_list(const py::handle& h, const char* what) {
  auto arr = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(h);
  if (!arr || arr.ndim() != 1) throw RoundingError(ErrorCode::InvalidInput, std::string("delta[") + what + "] must be a 1-d array of ids");
  return std::vector<int>(arr.data(), arr.data() + arr.size());
}

MeshDelta delta_from_dict(const py::dict& d) {
  MeshDelta out;
  out.input_vertices = d["input_vertices"].cast<int>(), out.input_facets = d["input_facets"].cast<int>();
  out.removed = int_list(d["removed"], "removed"), out.freed = int_list(d["freed"], "freed"), out.moved = int_list(d["moved"], "moved");
  out.moved_to = to_vecs(to_points(d["moved_to"], "delta['moved_to']"));
  out.new_points = to_vecs(to_points(d["new_points"], "delta['new_points']"));
  const Triangles added = to_triangles(d["added"]);
  for (Eigen::Index i = 0; i < added.rows(); ++i) out.added.push_back({added(i, 0), added(i, 1), added(i, 2)});
  if (out.moved.size() != out.moved_to.size()) throw RoundingError(ErrorCode::InvalidInput, "delta['moved'] and delta['moved_to'] differ in length");
  return out;
}

py::tuple apply_delta_py(const py::array& vertices, const py::array& triangles, const py::dict& delta) {
  const Points V = to_points(vertices, "vertices");
  const Triangles F = to_triangles(triangles);
  const MeshDelta d = delta_from_dict(delta);
  Points V_out;
  Triangles F_out;
  {
    py::gil_scoped_release release;
    apply_delta(V, F, d, V_out, F_out);
  }
  return py::make_tuple(py::array_t<double>(py::cast(V_out)), py::cast(F_out));
}

py::dict round_edges_py(const py::array& vertices, const py::array& triangles, const py::array& seeds, double radius,
                        double tolerance, double feature_angle, double reach, const py::object& radius_law, long max_new_facets,
                        const py::object& cancel, bool arrays, const py::object& band) {
  Call c = to_call(vertices, triangles, seeds, radius, tolerance, feature_angle, reach, radius_law, max_new_facets, cancel, band);
  c.opt.write_arrays = arrays;
  RoundResult res;
  {
    py::gil_scoped_release release;
    res = guarded([&] { return round_edges(c.V, c.F, c.seeds, c.opt); });
  }
  return result_dict(res, arrays, true);
}

// The work budget (0: the default) and the cancel token (None: none) into the options.
void set_budget_and_cancel(RoundOptions& opt, long max_new_facets, const py::object& cancel) {
  if (max_new_facets > 0) opt.max_new_facets = max_new_facets;  // 0: the default budget
  if (!cancel.is_none()) {
    if (!py::isinstance<CancelToken>(cancel)) throw RoundingError(ErrorCode::InvalidInput, "cancel must be a CancelToken or None");
    const std::atomic<bool>* flag = &cancel.cast<CancelToken&>().flag;  // the caller's reference outlives the call
    opt.cancelled = [flag] { return flag->load(std::memory_order_relaxed); };
  }
}

py::dict quality_dict(const ElementQuality& q) {
  py::dict d;
  d["elements"] = q.elements, d["quads"] = q.quads, d["triangles"] = q.elements - q.quads;
  d["min_angle_deg"] = q.min_angle_deg, d["max_angle_deg"] = q.max_angle_deg;
  d["max_aspect_ratio"] = q.max_aspect_ratio, d["max_warpage_deg"] = q.max_warpage_deg, d["min_side"] = q.min_side;
  return d;
}

// element_quality over (n, 3) points and (e, 4) node indices (-1 fourth: a triangle).
py::dict element_quality_py(const py::array& points, const py::array& elements) {
  const Points P = to_points(points, "points");
  auto e = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(elements);
  if (!e || e.ndim() != 2 || e.shape(1) != 4) throw RoundingError(ErrorCode::InvalidInput, "elements must be an (e, 4) array of node indices");
  std::vector<std::array<int, 4>> els(e.shape(0));
  for (py::ssize_t i = 0; i < e.shape(0); ++i)
    for (int k = 0; k < 4; ++k) {
      const long long id = e.at(i, k);
      if (id < (k == 3 ? -1 : 0) || id >= P.rows())
        throw RoundingError(ErrorCode::InvalidInput, "element " + std::to_string(i) + " refers to point " + std::to_string(id) + ", not in points");
      els[i][k] = int(id);
    }
  return quality_dict(element_quality(P, els));
}

// A RoundResult as the dict CONTRACT.md describes (round_edges' and change_radius' output); `arrays`: the
// whole mesh as arrays too, `with_delta`: the delta (an edit of the caller's input).
py::dict result_dict(const RoundResult& res, bool arrays, bool with_delta) {
  py::dict out;
  out["vertices"] = arrays ? py::object(py::array_t<double>(py::cast(res.vertices))) : py::object(py::none());
  out["triangles"] = arrays ? py::object(py::cast(res.triangles)) : py::object(py::none());
  out["delta"] = with_delta ? py::object(delta_dict(res.delta)) : py::object(py::none());
  py::list faces, spines, contacts, chains, closed, chain_reports;
  for (const RoundedChain& c : res.chains) {
    faces.append(py::bytes(c.brep).attr("decode")("ascii"));
    spines.append(polyline(c.spine));
    contacts.append(py::make_tuple(polyline(c.contacts[0]), polyline(c.contacts[1])));
    chains.append(polyline(c.chain));
    closed.append(c.report.closed);
    const ChainReport& r = c.report;
    py::dict d;
    d["closed"] = r.closed, d["length"] = r.length, d["stations"] = r.stations;
    d["facets_removed"] = r.facets_removed, d["facets_cut"] = r.facets_cut, d["facets_added"] = r.facets_added;
    d["vertices_snapped"] = r.vertices_snapped;
    d["contacts_on_edges"] = r.contacts_on_edges, d["contacts_on_vertices"] = r.contacts_on_vertices;
    d["surface_deviation"] = r.surface_deviation, d["mesh_deviation"] = r.mesh_deviation;
    d["profile_rows"] = r.profile_rows, d["gap_facets"] = r.gap_facets, d["open_gaps"] = r.open_gaps;
    d["edges_flipped"] = r.edges_flipped, d["vertices_removed"] = r.vertices_removed, d["vertices_slid"] = r.vertices_slid;
    d["thin_facets"] = r.thin_facets, d["reach_for_room"] = r.reach_for_room;
    d["cusp_facets"] = r.cusp_facets, d["cusp_angle_deg"] = r.cusp_angle_deg;
    d["min_angle_at_reach_for_room"] = r.min_angle_at_reach_for_room;
    chain_reports.append(d);
  }
  out["faces"] = faces, out["spines"] = spines, out["contacts"] = contacts, out["chains"] = chains, out["closed"] = closed;
  const RoundReport& r = res.report;
  py::dict rep;
  rep["chains"] = int(res.chains.size());
  rep["facets_removed"] = r.facets_removed, rep["facets_added"] = r.facets_added;
  rep["max_deviation"] = r.max_deviation, rep["min_new_angle_deg"] = r.min_new_angle_deg;
  rep["min_input_angle_deg"] = r.min_input_angle_deg;
  rep["input_forces_small_angles"] = r.input_forces_small_angles;
  rep["thin_facets"] = r.thin_facets, rep["thin_facets_short_of_room"] = r.thin_facets_short_of_room;
  rep["cusp_facets"] = r.cusp_facets, rep["cusp_angle_deg"] = r.cusp_angle_deg;
  rep["reach_for_room"] = r.reach_for_room;
  rep["seconds_total"] = r.seconds_total, rep["seconds_per_pass"] = r.seconds;
  rep["per_chain"] = chain_reports;
  py::list corners, corner_faces;
  for (const CornerReport& c : r.corners) {
    if (!c.brep.empty()) corner_faces.append(py::bytes(c.brep).attr("decode")("ascii"));
    py::dict d;
    d["vertex"] = py::make_tuple(c.vertex.x(), c.vertex.y(), c.vertex.z()), d["kind"] = c.kind, d["chains"] = c.chains;
    d["radius"] = c.radius, d["seam_vertices"] = c.seam_vertices, d["deviation"] = c.deviation;
    d["normal_jump_deg"] = c.normal_jump_deg, d["seam_turn_deg"] = c.seam_turn_deg;
    corners.append(d);
  }
  rep["corners"] = corners;
  rep["band_quality"] = quality_dict(r.band);
  out["report"] = rep;
  out["corner_faces"] = corner_faces;
  return out;
}

const char* end_name(ChainEnd e) {
  switch (e) {
    case ChainEnd::Junction: return "junction";
    case ChainEnd::Boundary: return "boundary";
    case ChainEnd::Turn: return "turn";
    default: return "fade";
  }
}

py::list chain_list(const std::vector<SharpChain>& chains) {
  py::list out;
  for (const SharpChain& c : chains) {
    py::dict d;
    d["points"] = polyline(c.points);
    d["closed"] = c.closed;
    if (!c.closed) d["ends"] = py::make_tuple(end_name(c.start_end), end_name(c.end_end));
    out.append(d);
  }
  return out;
}

py::list trace_chains_py(const py::array& vertices, const py::array& triangles, const py::array& seeds, double feature_angle,
                         double search_radius) {
  const Points V = to_points(vertices, "vertices");
  const Triangles F = to_triangles(triangles);
  const Points S = to_points(seeds, "seeds");
  return chain_list(guarded([&] { return find_chains(V, F, to_vecs(S), feature_angle, search_radius); }));
}

// plan_network (round.h): {'chains': [as trace_chains], 'corners': [{'vertex', 'kind', 'chains'}], 'refusal': str | None}.
py::dict plan_network_py(const py::array& vertices, const py::array& triangles, const py::array& seeds, double radius, double tolerance,
                         double feature_angle, double reach, const py::object& radius_law, const py::object& band) {
  const Call c = to_call(vertices, triangles, seeds, radius, tolerance, feature_angle, reach, radius_law, 0, py::none(), band);
  const NetworkPlan plan = guarded([&] { return plan_network(c.V, c.F, c.seeds, c.opt); });
  py::list corners;
  for (const PlannedCorner& k : plan.corners) {
    py::dict d;
    d["vertex"] = py::make_tuple(k.vertex.x(), k.vertex.y(), k.vertex.z());
    d["kind"] = k.kind;
    d["chains"] = k.chains;
    corners.append(d);
  }
  py::dict out;
  out["chains"] = chain_list(plan.chains);
  out["corners"] = corners;
  out["refusal"] = plan.refused ? py::object(py::str(plan.refusal)) : py::object(py::none());
  return out;
}

// max_radius (issue 16): one dict per chain, see max_radius.h.
py::list max_radius_py(const py::array& vertices, const py::array& triangles, const py::array& seeds, double feature_angle,
                       double reach, double precision, int min_stations) {
  const Points V = to_points(vertices, "vertices");
  const Triangles F = to_triangles(triangles);
  const Points S = to_points(seeds, "seeds");
  MaxRadiusOptions o;
  o.feature_angle_deg = feature_angle, o.reach = reach, o.precision = precision, o.min_stations = min_stations;
  std::vector<ChainRoom> rooms;
  {
    py::gil_scoped_release release;
    rooms = guarded([&] { return max_radius(V, F, to_vecs(S), o); });
  }
  py::list out;
  for (const ChainRoom& c : rooms) {
    py::dict d;
    d["radius"] = c.radius, d["radius_refused"] = c.radius_refused, d["why"] = room_limit_name(c.why);
    d["where"] = py::make_tuple(c.where.x(), c.where.y(), c.where.z());
    d["chain_point"] = py::make_tuple(c.chain_point.x(), c.chain_point.y(), c.chain_point.z());
    d["curvature_radius"] = c.curvature_radius, d["side"] = c.side;
    d["stations"] = c.stations, d["balls_solved"] = c.balls_solved, d["collections"] = c.collections;
    d["points"] = polyline(c.chain), d["closed"] = c.closed;
    out.append(d);
  }
  return out;
}

// ------------------------------------------------------------------------------ change_radius (sharpen.h)
py::dict strip_dict(const StripReport& s) {
  py::dict d;
  d["found_radius"] = s.found_radius, d["radius_min"] = s.radius_min, d["radius_max"] = s.radius_max;
  d["constant"] = s.constant, d["fit_residual"] = s.fit_residual;
  py::list law;
  for (size_t i = 0; i < s.law_s.size(); ++i)
    law.append(py::make_tuple(s.law_points[i].x(), s.law_points[i].y(), s.law_points[i].z(), s.law_r[i]));
  d["law"] = law;
  d["opening_deg"] = s.opening_deg, d["convex"] = s.convex;
  d["corner"] = polyline({s.corner[0], s.corner[1]});
  d["corner_line"] = polyline(s.corner_line);
  d["mitres"] = s.mitres;
  d["strip_facets"] = s.strip_facets, d["measured_vertices"] = s.measured_vertices;
  d["border_vertices"] = py::make_tuple(s.border_vertices[0], s.border_vertices[1]);
  d["end_faces"] = s.end_faces, d["facets_split"] = s.facets_split, d["end_facets_remeshed"] = s.end_facets_remeshed;
  d["points_merged"] = s.points_merged;
  d["border_flips"] = s.border_flips;
  d["recognised"] = s.recognised;
  return d;
}

py::dict change_radius_py(const py::array& vertices, const py::array& triangles, const py::array& seeds, double radius, double tolerance,
                          double feature_angle, double reach, const py::object& radius_law, long max_new_facets, const py::object& cancel,
                          double strip_turn, double flat_angle, double fit_tolerance, const py::object& band, bool arrays) {
  Call c = to_call(vertices, triangles, seeds, radius, tolerance, feature_angle, reach, radius_law, max_new_facets, cancel, band);
  c.opt.write_arrays = arrays;
  SharpenOptions so;
  so.strip_turn_deg = strip_turn, so.flat_deg = flat_angle, so.fit_tolerance = fit_tolerance;
  ChangeRadiusResult res;
  {
    py::gil_scoped_release release;
    res = guarded([&] { return change_radius(c.V, c.F, c.seeds, c.opt, so); });
  }
  py::dict out = result_dict(res.round, arrays, true);
  py::list strips;
  for (const StripReport& s : res.strips) strips.append(strip_dict(s));
  out["strips"] = strips;
  out["seconds_sharpen"] = res.seconds_sharpen;
  return out;
}

}  // namespace

// Solver decks (deck_bindings.cpp).
void bind_decks(py::module_& m);

// RoundingError for Python: a ValueError with the message and `.code` (error_code_name), raised from C++
// and from the workbench's own checks alike.
const char* kErrorClass = R"(
class RoundingError(ValueError):
    """A rounding could not be made: str(error) names the cause and the place, .code is one of the
    documented codes (invalid_input, no_sharp_edge, radius_too_large, ...)."""

    def __init__(self, message, code="invalid_input"):
        super().__init__(message)
        self.code = code
)";

PYBIND11_MODULE(_meshround_core, m) {
  m.doc() = "MeshRound engine: rolling-ball rounding of sharp-edge chains on triangle meshes";
  py::dict scope;
  scope["__name__"] = m.attr("__name__");
  py::exec(kErrorClass, scope, scope);
  // Kept for the interpreter's lifetime (never destroyed after Python has finalised).
  static py::object& error_class = *new py::object(scope["RoundingError"]);
  m.attr("RoundingError") = error_class;
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const RoundingError& e) {
      py::object err = error_class(e.what(), error_code_name(e.code));
      PyErr_SetObject(error_class.ptr(), err.ptr());
    }
  });
  py::class_<CancelToken>(m, "CancelToken",
                          "Stops a running round_edges(cancel=token) from another thread: token.cancel(); the run then "
                          "raises RoundingError with code 'cancelled' within about 0.1 s. One token per run; thread-safe.")
      .def(py::init<>())
      .def("cancel", [](CancelToken& t) { t.flag.store(true); }, "Ask the run(s) given this token to stop.")
      .def_property_readonly("is_cancelled", [](const CancelToken& t) { return t.flag.load(); })
      .def("__repr__", [](const CancelToken& t) {
        return std::string("<CancelToken ") + (t.flag.load() ? "cancelled" : "not cancelled") + ">";
      });
  m.def("round_edges", &round_edges_py, py::arg("vertices"), py::arg("triangles"), py::arg("seeds"), py::arg("radius"),
        py::arg("tolerance") = 0.0, py::arg("feature_angle") = 30.0, py::arg("reach") = 3.0,
        py::arg("radius_law") = py::none(), py::arg("max_new_facets") = 0, py::arg("cancel") = py::none(), py::arg("arrays") = true,
        py::arg("band") = py::none(),
        "Round the chains of sharp edges the seeds select. See CONTRACT.md for the arrays and the report.");
  m.def("change_radius", &change_radius_py, py::arg("vertices"), py::arg("triangles"), py::arg("seeds"), py::arg("radius"),
        py::arg("tolerance") = 0.0, py::arg("feature_angle") = 30.0, py::arg("reach") = 3.0, py::arg("radius_law") = py::none(),
        py::arg("max_new_facets") = 0, py::arg("cancel") = py::none(), py::arg("strip_turn") = SharpenOptions{}.strip_turn_deg,
        py::arg("flat_angle") = SharpenOptions{}.flat_deg, py::arg("fit_tolerance") = SharpenOptions{}.fit_tolerance,
        py::arg("band") = py::none(), py::arg("arrays") = true,
        "Sharpen the existing rounds the seeds pick, then round them at `radius` (0: sharpen only); round_edges' dict plus 'strips'.");
  m.def("apply_delta", &apply_delta_py, py::arg("vertices"), py::arg("triangles"), py::arg("delta"),
        "The rounded mesh (vertices, triangles) from the input arrays and round_edges' res['delta'] (CONTRACT.md).");
  m.attr("MIN_REACH") = kMinReach;
  m.def("validate_options", [](double radius, double tolerance, double feature_angle, double reach,
                               const py::object& radius_law, const py::object& band) {
          validate_options(to_options(radius, tolerance, feature_angle, reach, radius_law, band));
        }, py::arg("radius") = 1.0, py::arg("tolerance") = 0.0, py::arg("feature_angle") = 30.0, py::arg("reach") = 3.0,
        py::arg("radius_law") = py::none(), py::arg("band") = py::none(),
        "Raise RoundingError (invalid_input) for an option out of range, as round_edges would.");
  m.def("trace_chains", &trace_chains_py, py::arg("vertices"), py::arg("triangles"), py::arg("seeds"),
        py::arg("feature_angle") = 30.0, py::arg("search_radius") = 0.0, "The sharp-edge chains the seeds select: [{'points': (c, 3), 'closed': bool}].");
  m.def("plan_network", &plan_network_py, py::arg("vertices"), py::arg("triangles"), py::arg("seeds"), py::arg("radius"),
        py::arg("tolerance") = 0.0, py::arg("feature_angle") = 30.0, py::arg("reach") = 3.0, py::arg("radius_law") = py::none(),
        py::arg("band") = py::none(), "What round_edges will make of the chains the seeds select: the chains, each corner's blend, or the corner it refuses.");
  bind_decks(m);
  m.def("element_quality", &element_quality_py, py::arg("points"), py::arg("elements"),
        "Element quality as CAE checks it (element_quality.h): smallest/largest angle, aspect ratio, quads' warpage, shortest side.");
  m.def("max_radius", &max_radius_py, py::arg("vertices"), py::arg("triangles"), py::arg("seeds"), py::arg("feature_angle") = 30.0,
        py::arg("reach") = 3.0, py::arg("precision") = 1e-4, py::arg("min_stations") = 256,
        "The largest radius each chain the seeds select can be rounded with, what stops it and where (max_radius.h).");
}
