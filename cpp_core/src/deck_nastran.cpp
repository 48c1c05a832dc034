// Nastran bulk data: GRID, CTRIA3, CQUAD4, PSHELL, SET1 and SET3 (deck_nastran_sets.cpp) in small
// (8-column), large (`*`, 16-column) and free (comma) fields, with continuation lines; INCLUDE '<file>'.
// Before BEGIN BULK (when the file has one) only INCLUDE is read; after ENDDATA nothing. Every other card
// is kept as it is.
#include <cstdio>
#include <algorithm>
#include <deque>

#include "deck_text.h"

namespace meshround::decktext {

namespace {

struct Record {
  int first = -1, last = -1;   // lines
  std::vector<int> lines;      // the record's own lines (comments between them not included)
};

bool blank(std::string_view s) { return trim(s).empty(); }

// Cards whose first field is an element ID in the one numbering all elements share: C... (but CORD...) and
// the rigid elements.
bool is_other_element(const std::string& name) {
  if (!name.empty() && name[0] == 'C') return name.rfind("CORD", 0) != 0;
  for (const char* rigid : {"RBAR", "RBAR1", "RBE1", "RBE2", "RBE3", "RROD", "RSPLINE", "RTRPLT", "RTRPLT1", "PLOTEL"})
    if (name == rigid) return true;
  return false;
}

// A line that continues the record before it: '+' or '*' in column 1, a free-field ',' first, or a
// blank first field followed by data.
bool is_continuation(std::string_view line) {
  if (line.empty()) return false;
  if (line[0] == '+' || line[0] == '*' || line[0] == ',') return true;
  return blank(column(line, 0, 8)) && !blank(line);
}

struct NasReader {
  NasReader(Reader& reader, NastranSets& shared, int f, bool in_bulk) : r(reader), sets(shared), file(f), bulk(in_bulk) {}
  Reader& r;
  NastranSets& sets;
  int file;
  bool bulk;  // inside the bulk data section

  const DeckFile& f() const { return r.deck.files[file]; }
  Deck& d() { return r.deck; }

  std::deque<std::string> expanded;  // tab-expanded lines of the record being read (fields view them)
  std::vector<int> field_line;       // the line of each data field of the record being read
  int overflow = -1;                 // a free-field line of it with more than 10 fields (-1: none)

  // A fixed-field line with its tabs expanded to the next 8-column field, as Nastran reads it.
  std::string_view expand_tabs(std::string_view line) {
    std::string out;
    for (char c : line) {
      if (c == '\t') out.append(8 - out.size() % 8, ' ');
      else out += c;
    }
    expanded.push_back(std::move(out));
    return expanded.back();
  }

  // The data fields of a record (field 2 on, continuation markers left out), and its style.
  std::vector<std::string_view> data_fields(const Record& rec, std::string& name, FieldStyle& style) {
    std::vector<std::string_view> out;
    field_line.clear();
    overflow = -1;
    for (size_t k = 0; k < rec.lines.size(); ++k) {
      const std::string_view line = line_of(f(), rec.lines[k]);
      field_line.resize(out.size(), rec.lines[k > 0 ? k - 1 : 0]);
      if (line.find(',') != std::string_view::npos) {
        auto toks = split_commas(line);
        if (k == 0) name = upper(toks[0]), style = FieldStyle::Free;
        const bool large = !toks[0].empty() && toks[0].back() == '*';
        const size_t per = large ? 4 : 8;
        for (size_t j = 1; j < toks.size() && j <= per; ++j) out.push_back(toks[j]);
        for (size_t j = per + 2; j < toks.size() && overflow < 0; ++j)
          if (!toks[j].empty()) overflow = rec.lines[k];
        continue;
      }
      std::string_view line_fixed = line;
      if (line.find('\t') != std::string_view::npos) line_fixed = expand_tabs(line);
      const std::string_view head = trim(column(line_fixed, 0, 8));
      const bool large = !head.empty() && head.back() == '*';
      if (k == 0) name = upper(head), style = large ? FieldStyle::Long : FieldStyle::Fixed;
      const size_t w = large ? 16 : 8, per = large ? 4 : 8;
      for (size_t j = 0; j < per; ++j) out.push_back(trim(column(line_fixed, 8 + j * w, w)));
    }
    field_line.resize(out.size(), rec.lines.back());
    if (!name.empty() && name.back() == '*') name.pop_back();
    return out;
  }

  long long need_int(std::string_view s, int line, const char* what, bool blank_ok = false, long long dflt = 0) {
    long long v;
    if (!parse_int(s, v, blank_ok, dflt)) refuse(f(), line, std::string("bad ") + what + " '" + std::string(s) + "'");
    return v;
  }

  static std::string_view at(const std::vector<std::string_view>& v, size_t k) { return k < v.size() ? v[k] : std::string_view(); }

  void record(const Record& rec);
  void run();
};

void NasReader::record(const Record& rec) {
  std::string name;
  FieldStyle style = FieldStyle::Fixed;
  expanded.clear();
  const auto fs = data_fields(rec, name, style);
  const int line = rec.first;
  if (name == "GRID") {
    DeckNode n;
    n.id = need_int(at(fs, 0), line, "GRID ID");
    if (n.id <= 0) refuse(f(), line, "GRID ID must be positive, got " + std::to_string(n.id));
    const long long cp = need_int(at(fs, 1), line, "GRID CP", true);
    if (cp != 0) refuse(f(), line, "GRID " + std::to_string(n.id) + " is given in coordinate system " + std::to_string(cp) + " (only the basic system, CP blank or 0, is supported)");
    for (int k = 0; k < 3; ++k)
      if (!parse_real(at(fs, 2 + k), n.xyz[k], true)) refuse(f(), line, "bad GRID coordinate '" + std::string(at(fs, 2 + k)) + "'");
    n.file = file, n.line = rec.first, n.lines = rec.last - rec.first + 1, n.style = style;
    d().nodes.push_back(n);
  } else if (name == "CTRIA3" || name == "CQUAD4") {
    DeckShell s;
    s.count = name == "CQUAD4" ? 4 : 3;
    s.id = need_int(at(fs, 0), line, "element ID");
    if (s.id <= 0) refuse(f(), line, "element ID must be positive, got " + std::to_string(s.id));
    s.part = need_int(at(fs, 1), line, "PID", true, s.id);  // blank PID is the element ID
    for (int k = 0; k < s.count; ++k) {
      s.nodes[k] = need_int(at(fs, 2 + k), line, "grid ID");
      if (s.nodes[k] <= 0) refuse(f(), line, name + " " + std::to_string(s.id) + " has no grid " + std::to_string(k + 1));
    }
    s.file = file, s.line = rec.first, s.lines = rec.last - rec.first + 1, s.style = style;
    d().shells.push_back(s);
  } else if (name == "PSHELL") {
    DeckPart p;
    p.id = need_int(at(fs, 0), line, "PSHELL PID");
    d().parts.push_back(p);
  } else if (name == "SET1" || name == "SET3") {
    sets.card(d(), file, rec.first, rec.last, name, style, fs, field_line, overflow);
  } else if (name == "SPLINE1" || name == "SPLINE2" || name == "SPLINE4" || name == "SPLINE5") {
    long long setg;  // field 6: the SET1 of the structural grids the spline connects
    if (parse_int(at(fs, 4), setg)) sets.grid_set_refs.push_back(setg);
  } else if (is_other_element(name)) {
    long long id;
    if (parse_int(at(fs, 0), id)) {
      d().max_element_id = std::max(d().max_element_id, id);
      sets.other_elements.push_back(id);
    }
  }
}

void NasReader::run() {
  const int n = f().lines();
  if (!bulk) {  // a main file without BEGIN BULK is bulk data throughout
    bool has_begin = false;
    for (int i = 0; i < n && !has_begin; ++i) {
      const std::string_view t = trim(line_of(f(), i));
      has_begin = starts_with_ci(t, "BEGIN") && upper(t).find("BULK") != std::string::npos;
    }
    bulk = !has_begin;
  }
  Record rec;
  auto flush = [&] {
    if (rec.first >= 0 && bulk) record(rec);
    rec = Record();
  };
  for (int i = 0; i < n; ++i) {
    const std::string_view text = line_of(f(), i);
    if (text.empty() || text[0] == '$' || blank(text)) continue;
    const std::string_view t = trim(text);
    if (starts_with_ci(t, "INCLUDE")) {
      flush();
      // The quoted name may continue on the next lines (leading and trailing blanks not part of it).
      std::string quoted(t);
      const int first = i;
      while (std::count(quoted.begin(), quoted.end(), '\'') == 1 && i + 1 < n) quoted += std::string(trim(line_of(f(), ++i)));
      const size_t a = quoted.find('\''), b = quoted.rfind('\'');
      if (a == std::string::npos || b <= a) refuse(f(), first, "INCLUDE needs a quoted file name");
      const int inc = r.include(file, first, quoted.substr(a + 1, b - a - 1));
      ++r.depth;
      NasReader sub(r, sets, inc, bulk);
      sub.run();
      --r.depth;
      continue;
    }
    if (!bulk) {
      if (starts_with_ci(t, "BEGIN") && upper(t).find("BULK") != std::string::npos) bulk = true;
      continue;
    }
    if (starts_with_ci(t, "ENDDATA")) {
      flush();
      return;
    }
    if (rec.first >= 0 && is_continuation(text)) {
      rec.lines.push_back(i), rec.last = i;
      continue;
    }
    flush();
    if (is_continuation(text)) refuse(f(), i, "a continuation line without a card before it");
    rec.first = rec.last = i;
    rec.lines.push_back(i);
  }
  flush();
}

// A card laid out in a style: small field (8 columns, 8 data fields a line) when every field fits 8 columns
// and the style is Fixed; else large (`*`, 16 columns, 4 a line) when they fit 16 and the style is not
// Free; else free field (commas, 8 a line). Continuation lines have a blank field 1 (`*` in large field).
std::string card_text(const std::string& name, const std::vector<std::string>& fields, FieldStyle style, const std::string& eol) {
  size_t widest = 0;
  for (const std::string& x : fields) widest = std::max(widest, x.size());
  const size_t w = style == FieldStyle::Fixed && widest <= 8 ? 8 : style != FieldStyle::Free && widest <= 16 ? 16 : 0;
  if (w == 0) {
    std::string out = name;
    for (size_t k = 0; k < fields.size(); ++k) out += (k && k % 8 == 0 ? eol + "," : ",") + fields[k];
    return out + eol;
  }
  const size_t per = w == 8 ? 8 : 4;
  std::string out, line = w == 8 ? name : name + "*";
  auto flush = [&] {
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out += line + eol;
  };
  line.resize(8, ' ');
  for (size_t k = 0; k < fields.size(); ++k) {
    if (k && k % per == 0) flush(), line = w == 8 ? "        " : "*       ";
    line += fields[k];
    line.resize(8 + (k % per + 1) * w, ' ');
  }
  flush();
  return out;
}

std::string large_real(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%16.8E", x);
  return buf;
}

}  // namespace

void read_nastran(Reader& r, int file) {
  NastranSets sets;
  NasReader reader(r, sets, file, false);
  reader.run();
  sets.resolve(r.deck);
}

std::string nastran_node(const DeckNode& n, FieldStyle style, const std::string& eol) {
  if (style == FieldStyle::Free) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "GRID,%lld,,%.17g,%.17g,%.17g", n.id, n.xyz.x(), n.xyz.y(), n.xyz.z());
    return buf + eol;
  }
  // Large field for new grids in fixed decks too: 16 columns keep 9 significant digits (small: 8 columns).
  if (std::to_string(n.id).size() > 16) throw RoundingError(ErrorCode::InvalidInput, "node ID too large for Nastran");
  char id[32];
  std::snprintf(id, sizeof id, "%16lld", n.id);
  return "GRID*   " + std::string(id) + std::string(16, ' ') + large_real(n.xyz.x()) + large_real(n.xyz.y()) + eol +
         "*       " + large_real(n.xyz.z()) + eol;
}

std::string nastran_shell(const DeckShell& s, FieldStyle style, const std::string& eol) {
  std::vector<std::string> v = {std::to_string(s.id), std::to_string(s.part)};
  for (int k = 0; k < s.count; ++k) v.push_back(std::to_string(s.nodes[k]));
  return card_text(s.count == 4 ? "CQUAD4" : "CTRIA3", v, style, eol);
}

std::string nastran_set(const DeckSet& s, const std::vector<long long>& ids, const std::string& eol) {
  const std::string name = s.des.empty() ? "SET1" : "SET3";
  if (ids.empty()) throw RoundingError(ErrorCode::InvalidInput, "deck edit: " + name + " " + std::to_string(s.id) + " would hold no ID");
  std::vector<std::string> v = {std::to_string(s.id)};
  if (!s.des.empty()) v.push_back(s.des);
  // Runs of three or more consecutive IDs as "first THRU last" -- in a SET1 of known kind only, whose IDs
  // the deck defines: a range leaves out IDs the deck does not define (a SET3 may list such IDs).
  const bool ranges = s.kind_known && s.des.empty();
  for (size_t k = 0; k < ids.size();) {
    size_t j = k;
    while (ranges && j + 1 < ids.size() && ids[j] < ids[j + 1] && ids[j + 1] == ids[j] + 1) ++j;
    if (j - k >= 2) {
      v.insert(v.end(), {std::to_string(ids[k]), "THRU", std::to_string(ids[j])});
    } else {
      for (size_t i = k; i <= j; ++i) v.push_back(std::to_string(ids[i]));
    }
    k = j + 1;
  }
  return card_text(name, v, s.style, eol);
}

}  // namespace meshround::decktext
