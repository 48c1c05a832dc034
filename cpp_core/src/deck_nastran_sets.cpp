// Nastran SET1 (SID, IDs) and SET3 (SID, DES, IDs) with THRU ranges: read card by card while the bulk data
// is read, then resolved against the whole deck's grids and elements (deck.h, DeckSet::kind_known).
// Kept as they are, not read: SET1 with SKIN, cards with OptiStruct's EXCEPT / ENDTHRU or with IDs not
// above 0 (ZAERO's SET1 has negative ones), SET3 of POINT or PROP (or another DES).
#include <algorithm>

#include "deck_text.h"

namespace meshround::decktext {

void NastranSets::card(Deck& d, int file, int first, int last, const std::string& name, FieldStyle style,
                       const std::vector<std::string_view>& fields, const std::vector<int>& field_line, int overflow) {
  const DeckFile& f = d.files[file];
  const auto line = [&](size_t k) { return k < field_line.size() ? field_line[k] : first; };
  const auto field = [&](size_t k) { return k < fields.size() ? fields[k] : std::string_view(); };
  if (overflow >= 0) refuse(f, overflow, name + ": more than 10 fields on a free-field line");
  long long sid;
  if (!parse_int(field(0), sid)) refuse(f, line(0), "bad " + name + " SID '" + std::string(field(0)) + "'");
  if (sid <= 0) refuse(f, line(0), name + " SID must be positive, got " + std::to_string(sid));
  const std::string what = name + " " + std::to_string(sid);
  DeckSet s;
  size_t k = 1;
  if (name == "SET3") {
    s.des = upper(field(1));
    if (s.des.empty()) refuse(f, line(1), what + " has no DES (GRID, ELEM, POINT or PROP)");
    if (s.des != "GRID" && s.des != "ELEM") return;
    k = 2;
  } else if (upper(field(1)) == "SKIN") {
    return;
  }
  Pending p;
  bool after_id = false;  // the last field read was an ID (a THRU may follow)
  for (; k < fields.size(); ++k) {
    if (fields[k].empty()) continue;
    const std::string word = upper(fields[k]);
    if (word == "EXCEPT" || word == "ENDTHRU") return;
    if (word == "THRU") {
      if (!after_id) refuse(f, line(k), what + ": THRU without an ID before it");
      size_t j = k + 1;
      while (j < fields.size() && fields[j].empty()) ++j;
      if (j >= fields.size()) refuse(f, line(k), what + ": THRU without an ID after it");
      long long to;
      if (!parse_int(fields[j], to)) refuse(f, line(j), "bad " + name + " ID '" + std::string(fields[j]) + "'");
      Item& range = p.items.back();
      if (to < range.first)
        refuse(f, line(j), what + ": bad THRU range " + std::to_string(range.first) + " THRU " + std::to_string(to));
      range.last = to, range.range = true;
      after_id = false;
      k = j;
      continue;
    }
    long long id;
    if (!parse_int(fields[k], id)) refuse(f, line(k), "bad " + name + " ID '" + std::string(fields[k]) + "'");
    if (id <= 0) return;
    p.items.push_back({id, id, false});
    after_id = true;
  }
  if (p.items.empty()) refuse(f, first, what + " lists no ID");
  s.id = sid, s.file = file, s.keyword_line = s.data_begin = first, s.data_end = last + 1, s.style = style;
  p.set = int(d.sets.size());
  d.sets.push_back(std::move(s));
  pending.push_back(std::move(p));
}

namespace {

// How one pending set reads as a set of one kind (IDs sorted, unique).
struct Reading {
  bool loose_all = true;   // every ID given alone is of the kind
  bool ranges_full = true; // every ID of every range is
  size_t count = 0;        // members
};

Reading read_as(const NastranSets::Pending& p, const std::vector<long long>& ids) {
  Reading r;
  for (const NastranSets::Item& it : p.items) {
    const size_t n = size_t(std::upper_bound(ids.begin(), ids.end(), it.last) - std::lower_bound(ids.begin(), ids.end(), it.first));
    if (!it.range) r.loose_all = r.loose_all && n == 1, ++r.count;
    else r.ranges_full = r.ranges_full && (unsigned long long)n == (unsigned long long)(it.last - it.first) + 1, r.count += n;
  }
  return r;
}

// The members: IDs given alone as they are, ranges as the IDs of `kinds` in them (in order).
void members(const NastranSets::Pending& p, std::initializer_list<const std::vector<long long>*> kinds, const Deck& d,
             DeckSet& s) {
  for (const NastranSets::Item& it : p.items) {
    if (!it.range) {
      s.members.push_back(it.first);
      continue;
    }
    for (const std::vector<long long>* ids : kinds) {
      const auto a = std::lower_bound(ids->begin(), ids->end(), it.first), b = std::upper_bound(ids->begin(), ids->end(), it.last);
      if (s.members.size() + size_t(b - a) > size_t(kMaxGenerated))
        refuse(d.files[s.file], s.keyword_line, "a set of more than " + std::to_string(kMaxGenerated) + " IDs");
      s.members.insert(s.members.end(), a, b);
    }
  }
}

std::vector<long long> sorted_unique(std::vector<long long> v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

}  // namespace

void NastranSets::resolve(Deck& d) const {
  if (pending.empty()) return;
  std::vector<long long> grids, elements = other_elements;
  grids.reserve(d.nodes.size());
  for (const DeckNode& n : d.nodes) grids.push_back(n.id);
  for (const DeckShell& s : d.shells) elements.push_back(s.id);
  grids = sorted_unique(std::move(grids)), elements = sorted_unique(std::move(elements));
  const std::vector<long long> grid_sets = sorted_unique(grid_set_refs);
  for (const Pending& p : pending) {
    DeckSet& s = d.sets[p.set];
    if (!s.des.empty()) {
      s.of_nodes = s.des == "GRID";
      members(p, {s.of_nodes ? &grids : &elements}, d, s);
      continue;
    }
    const Reading g = read_as(p, grids), e = read_as(p, elements);
    const bool g_full = g.loose_all && g.ranges_full, e_full = e.loose_all && e.ranges_full;
    const bool g_some = g.loose_all && g.count > 0, e_some = e.loose_all && e.count > 0;
    s.kind_known = g_full != e_full || (!g_full && g_some != e_some);
    s.of_nodes = s.kind_known && (g_full != e_full ? g_full : g_some);
    if (!s.kind_known && g_some && std::binary_search(grid_sets.begin(), grid_sets.end(), s.id))
      s.kind_known = s.of_nodes = true;  // a spline's SETG: its grids
    if (!s.kind_known) members(p, {&grids, &elements}, d, s);
    else members(p, {s.of_nodes ? &grids : &elements}, d, s);
  }
}

}  // namespace meshround::decktext
