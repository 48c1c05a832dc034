// _meshround_core's solver-deck block (deck.h): read_deck / parse_deck -> Deck, Deck.arrays(), Deck.write().
// See CONTRACT.md, "Solver decks".
#include <functional>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "meshround/deck.h"

namespace py = pybind11;
using namespace meshround;

namespace {

template <class T>
py::array_t<T> column_of(size_t n, const std::function<T(size_t)>& get) {
  py::array_t<T> a{py::ssize_t(n)};
  T* p = a.mutable_data();
  for (size_t i = 0; i < n; ++i) p[i] = get(i);
  return a;
}

py::dict deck_arrays(const Deck& d) {
  const size_t n = d.nodes.size(), m = d.shells.size();
  py::dict out;
  out["format"] = deck_format_name(d.format);
  out["node_ids"] = column_of<long long>(n, [&](size_t i) { return d.nodes[i].id; });
  py::array_t<double> xyz({py::ssize_t(n), py::ssize_t(3)});
  double* p = xyz.mutable_data();
  for (size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) p[3 * i + k] = d.nodes[i].xyz[k];
  out["node_xyz"] = xyz;
  out["node_file"] = column_of<int>(n, [&](size_t i) { return d.nodes[i].file; });
  out["node_line"] = column_of<int>(n, [&](size_t i) { return d.nodes[i].line + 1; });
  out["shell_ids"] = column_of<long long>(m, [&](size_t i) { return d.shells[i].id; });
  out["shell_parts"] = column_of<long long>(m, [&](size_t i) { return d.shells[i].part; });
  out["shell_counts"] = column_of<int>(m, [&](size_t i) { return d.shells[i].count; });
  out["shell_file"] = column_of<int>(m, [&](size_t i) { return d.shells[i].file; });
  out["shell_line"] = column_of<int>(m, [&](size_t i) { return d.shells[i].line + 1; });
  out["node_span"] = column_of<int>(n, [&](size_t i) { return d.nodes[i].lines; });     // lines per record
  out["shell_span"] = column_of<int>(m, [&](size_t i) { return d.shells[i].lines; });
  py::array_t<long long> index({py::ssize_t(m), py::ssize_t(4)}), ids({py::ssize_t(m), py::ssize_t(4)});
  long long *pi = index.mutable_data(), *pd = ids.mutable_data();
  for (size_t i = 0; i < m; ++i)
    for (int k = 0; k < 4; ++k) pi[4 * i + k] = d.shells[i].node_index[k], pd[4 * i + k] = d.shells[i].nodes[k];
  out["shell_nodes"] = index;      // indices into node_ids (-1: a triangle's 4th)
  out["shell_node_ids"] = ids;     // the IDs (0: a triangle's 4th)
  py::list parts, sets, files;
  for (const DeckPart& p : d.parts) parts.append(py::make_tuple(p.id, p.name));
  for (const DeckSet& s : d.sets) {
    py::dict e;
    e["of_nodes"] = s.of_nodes, e["name"] = s.name, e["id"] = s.id, e["file"] = s.file, e["line"] = s.keyword_line + 1;
    e["kind_known"] = s.kind_known, e["des"] = s.des;
    e["members"] = py::array_t<long long>(py::ssize_t(s.members.size()), s.members.data());
    e["named_members"] = s.named_members;
    e["generate"] = s.generate;
    e["data_lines"] = py::make_tuple(s.data_begin + 1, s.data_end + 1);  // 1-based [first, end)
    sets.append(e);
  }
  for (const DeckFile& f : d.files) files.append(f.path);
  out["parts"] = parts, out["sets"] = sets, out["files"] = files;
  out["max_node_id"] = d.max_node_id, out["max_element_id"] = d.max_element_id;
  return out;
}

std::vector<long long> ids_of(const py::object& o) {
  if (o.is_none()) return {};
  auto a = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(o);
  if (!a || a.ndim() != 1) throw RoundingError(ErrorCode::InvalidInput, "IDs must be a 1-d array of whole numbers");
  return std::vector<long long>(a.data(), a.data() + a.size());
}

py::list deck_write(const Deck& d, const py::object& removed_nodes, const py::object& removed_shells, const py::object& node_ids,
                    const py::object& node_xyz, const py::object& shell_ids, const py::object& shell_parts,
                    const py::object& shell_nodes, const py::list& set_members) {
  DeckEdits e;
  e.removed_nodes = ids_of(removed_nodes), e.removed_shells = ids_of(removed_shells);
  const auto nid = ids_of(node_ids), sid = ids_of(shell_ids), spart = ids_of(shell_parts);
  if (!nid.empty()) {
    auto xyz = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(node_xyz);
    if (!xyz || xyz.ndim() != 2 || xyz.shape(0) != py::ssize_t(nid.size()) || xyz.shape(1) != 3)
      throw RoundingError(ErrorCode::InvalidInput, "new node coordinates must be an (n, 3) array, one row per new node ID");
    for (size_t i = 0; i < nid.size(); ++i) e.new_nodes.push_back({nid[i], Vec3(xyz.at(i, 0), xyz.at(i, 1), xyz.at(i, 2))});
  }
  if (!sid.empty()) {
    auto nodes = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(shell_nodes);
    if (!nodes || nodes.ndim() != 2 || nodes.shape(0) != py::ssize_t(sid.size()) || nodes.shape(1) != 4 || spart.size() != sid.size())
      throw RoundingError(ErrorCode::InvalidInput, "new elements need one part and one row of 4 node IDs (0 last for a triangle) per ID");
    for (size_t i = 0; i < sid.size(); ++i) {
      DeckShell s;
      s.id = sid[i], s.part = spart[i];
      for (int k = 0; k < 4; ++k) s.nodes[k] = nodes.at(i, k);
      s.count = s.nodes[3] > 0 ? 4 : 3;
      e.new_shells.push_back(s);
    }
  }
  for (const py::handle& item : set_members) {
    auto pair = item.cast<py::tuple>();
    e.set_members.push_back({pair[0].cast<int>(), ids_of(pair[1])});
  }
  std::vector<std::string> texts;
  {
    py::gil_scoped_release release;
    texts = write_deck(d, e);
  }
  py::list out;
  for (const std::string& t : texts) out.append(py::bytes(t));
  return out;
}

}  // namespace

void bind_decks(py::module_& m) {
  py::class_<Deck>(m, "Deck", "A solver deck read losslessly (deck.h); .arrays() indexes it, .write() emits it with edits.")
      .def_property_readonly("format", [](const Deck& d) { return deck_format_name(d.format); })
      .def_property_readonly("paths", [](const Deck& d) {
        std::vector<std::string> p;
        for (const DeckFile& f : d.files) p.push_back(f.path);
        return p;
      })
      .def("texts", [](const Deck& d) {
        py::list out;
        for (const DeckFile& f : d.files) out.append(py::bytes(f.text));
        return out;
      }, "Each file's bytes, as read.")
      .def("arrays", &deck_arrays, "Nodes, shells, parts and sets as numpy arrays and lists (CONTRACT.md).")
      .def("write", &deck_write, py::arg("removed_nodes") = py::none(), py::arg("removed_shells") = py::none(),
           py::arg("node_ids") = py::none(), py::arg("node_xyz") = py::none(), py::arg("shell_ids") = py::none(),
           py::arg("shell_parts") = py::none(), py::arg("shell_nodes") = py::none(), py::arg("set_members") = py::list(),
           "Each file's bytes with the edits applied; untouched lines byte-identical.");
  m.def("read_deck", [](const std::string& path) {
    py::gil_scoped_release release;
    return read_deck(path);
  }, py::arg("path"), "Read a solver deck (format by extension; includes followed). Raises RoundingError naming file:line.");
  m.def("parse_deck", [](const std::string& path, const py::bytes& text, const std::string& format) {
    DeckFormat f = format == "lsdyna" ? DeckFormat::LsDyna : format == "nastran" ? DeckFormat::Nastran : DeckFormat::Abaqus;
    if (format != "lsdyna" && format != "nastran" && format != "abaqus")
      throw RoundingError(ErrorCode::InvalidInput, "format must be lsdyna, nastran or abaqus");
    std::string t = text;
    py::gil_scoped_release release;
    return parse_deck(path, std::move(t), f, nullptr);
  }, py::arg("path"), py::arg("text"), py::arg("format"), "A deck from bytes in memory (includes refused by name).");
}
