// LS-DYNA keyword files: *NODE, *ELEMENT_SHELL (3 and 4 nodes, with THICKNESS/BETA/MCID/OFFSET/DOF
// cards), *PART, *SET_NODE(_LIST), *SET_SHELL(_LIST) (TITLE, GENERATE), *INCLUDE; standard, long (`+`,
// *KEYWORD LONG=Y), i10 (`%`, *KEYWORD I10=Y) and comma free-format lines. Everything else is kept.
#include <cstdio>
#include <cstring>

#include "deck_text.h"

namespace meshround::decktext {

namespace {

enum class Ctx { None, Node, Shell, Part, Set, Include, OtherElement };

struct Widths {
  size_t id, real, general;  // *NODE id, *NODE coordinates, shell fields and 10-column cards
};

Widths widths(FieldStyle s) {
  switch (s) {
    case FieldStyle::Long: return {20, 20, 20};
    case FieldStyle::I10: return {10, 16, 10};
    default: return {8, 16, 10};
  }
}

// *ELEMENT_ cards: 8 columns per field (standard), 20 (long), 10 (i10).
size_t shell_width(FieldStyle s) { return s == FieldStyle::Fixed ? 8 : widths(s).general; }

// Splits a data line into `out` (reused from line to line): commas if it has any, else columns of `first`
// then `rest` width.
const std::vector<std::string_view>& fields(std::string_view line, bool comma, size_t count, size_t first, size_t rest,
                                            std::vector<std::string_view>& out) {
  if (comma) {
    split_commas(line, out);
    return out;
  }
  out.clear();
  size_t at = 0;
  for (size_t k = 0; k < count && at < line.size(); ++k) {
    const size_t w = k == 0 ? first : rest;
    out.push_back(trim(column(line, at, w)));
    at += w;
  }
  return out;
}

std::string_view field(const std::vector<std::string_view>& f, size_t k) { return k < f.size() ? f[k] : std::string_view(); }

struct LsReader {
  LsReader(Reader& reader, int f, FieldStyle g) : r(reader), file(f), global(g) {}
  Reader& r;
  int file;
  FieldStyle global;  // from *KEYWORD
  Ctx ctx = Ctx::None;
  FieldStyle style = FieldStyle::Fixed;
  int extra_cards = 0;      // *ELEMENT_SHELL_<options>: cards after the node card of each record
  int pending = 0;          // of those, still to come for the last record
  int part_state = 0;       // *PART: 0 title next, 1 card next, 2 done (options other than plain *PART)
  bool plain_part = true;
  std::string part_title;
  int set_state = 0;        // 0 title next (TITLE), 1 header next, 2 data
  int set = -1;             // the set being read
  bool set_title = false;
  std::vector<std::string_view> buffer;  // the fields of the line being read
  bool comma = false;                    // ... and whether it is comma-separated

  const std::vector<std::string_view>& fields(std::string_view line, size_t count, size_t first, size_t rest) {
    comma = line.find(',') != std::string_view::npos;
    return decktext::fields(line, comma, count, first, rest, buffer);
  }
  const DeckFile& f() const { return r.deck.files[file]; }
  Deck& d() { return r.deck; }

  long long need_int(std::string_view s, int line, const char* what, bool blank_ok = false) {
    long long v;
    if (!parse_int(s, v, blank_ok)) refuse(f(), line, std::string("bad ") + what + " '" + std::string(s) + "'");
    return v;
  }

  void keyword(std::string_view text, int line);
  void node(std::string_view text, int line);
  void shell(std::string_view text, int line);
  void part(std::string_view text, int line);
  void set_line(std::string_view text, int line);
  void run();
};

void LsReader::keyword(std::string_view text, int line) {
  if (set >= 0 && d().sets[set].data_end < d().sets[set].data_begin) d().sets[set].data_end = d().sets[set].data_begin;
  set = -1;
  std::string_view rest = text.substr(1);
  size_t sp = 0;
  while (sp < rest.size() && rest[sp] != ' ' && rest[sp] != '\t') ++sp;
  std::string name = upper(rest.substr(0, sp));
  std::string_view after = trim(rest.substr(sp));
  style = global;
  char suffix = name.empty() ? 0 : name.back();
  if (after == "+" || after == "%" || after == "-") suffix = after[0];
  if (!name.empty() && (name.back() == '+' || name.back() == '%' || name.back() == '-')) name.pop_back();
  if (suffix == '+') style = FieldStyle::Long;
  if (suffix == '%') style = FieldStyle::I10;
  if (suffix == '-') style = FieldStyle::Fixed;
  ctx = Ctx::None;
  pending = 0;
  if (name == "KEYWORD") {
    const std::string opts = upper(after);
    if (opts.find("LONG=Y") != std::string::npos) global = FieldStyle::Long;
    if (opts.find("I10=Y") != std::string::npos) global = FieldStyle::I10;
  } else if (name == "NODE") {
    ctx = Ctx::Node;
  } else if (name.rfind("ELEMENT_SHELL", 0) == 0) {
    ctx = Ctx::Shell;
    bool thick = false, offset = false, dof = false;
    std::string_view opts = std::string_view(name).substr(13);
    while (!opts.empty()) {
      if (opts[0] != '_') refuse(f(), line, "*" + name + " is not an element keyword this reader knows");
      opts.remove_prefix(1);
      const size_t u = opts.find('_');
      const std::string_view o = opts.substr(0, u);
      if (o == "THICKNESS" || o == "BETA" || o == "MCID") thick = true;
      else if (o == "OFFSET") offset = true;
      else if (o == "DOF") dof = true;
      else refuse(f(), line, "*" + name + ": the shell option " + std::string(o) + " is not supported");
      opts = u == std::string_view::npos ? std::string_view() : opts.substr(u);
    }
    extra_cards = int(thick) + int(offset) + int(dof);
  } else if (name.rfind("ELEMENT_", 0) == 0) {
    ctx = Ctx::OtherElement;
  } else if (name == "PART" || name.rfind("PART_", 0) == 0) {
    ctx = Ctx::Part;
    plain_part = name == "PART";
    part_state = 0;
  } else if (name == "INCLUDE") {
    ctx = Ctx::Include;
  } else if (name.rfind("INCLUDE_", 0) == 0) {
    refuse(f(), line, "*" + name + " is not followed (only *INCLUDE is); inline the file or use *INCLUDE");
  } else if (name.rfind("SET_NODE", 0) == 0 || name.rfind("SET_SHELL", 0) == 0) {
    const bool nodes = name.rfind("SET_NODE", 0) == 0;
    std::string opts = name.substr(nodes ? 8 : 9);
    bool generate = false;
    set_title = false;
    for (const char* known : {"_LIST", "_GENERATE", "_TITLE"}) {
      const size_t at = opts.find(known);
      if (at == std::string::npos) continue;
      if (known[1] == 'G') generate = true;
      if (known[1] == 'T') set_title = true;
      opts.erase(at, std::strlen(known));
    }
    if (!opts.empty()) return;  // _ADD, _GENERAL, _INTERSECT, ...: kept as they are, not read
    ctx = Ctx::Set;
    set_state = set_title ? 0 : 1;
    DeckSet s;
    s.of_nodes = nodes, s.generate = generate, s.file = file, s.keyword_line = line, s.style = style;
    s.data_begin = line + 1, s.data_end = -1;
    d().sets.push_back(s);
    set = int(d().sets.size()) - 1;
  }
}

void LsReader::node(std::string_view text, int line) {
  const Widths w = widths(style);
  const auto& fs = fields(text, 4, w.id, w.real);
  DeckNode n;
  n.id = need_int(field(fs, 0), line, "node ID");
  if (n.id <= 0) refuse(f(), line, "node ID must be positive, got " + std::to_string(n.id));
  for (int k = 0; k < 3; ++k)
    if (!parse_real(field(fs, 1 + k), n.xyz[k])) refuse(f(), line, "bad coordinate '" + std::string(field(fs, 1 + k)) + "'");
  n.file = file, n.line = line;
  n.style = comma ? FieldStyle::Free : style;
  d().nodes.push_back(n);
}

void LsReader::shell(std::string_view text, int line) {
  if (pending > 0) {  // a THICKNESS/OFFSET/DOF card of the last record
    --pending;
    ++d().shells.back().lines;
    return;
  }
  const auto& fs = fields(text, 6, shell_width(style), shell_width(style));
  DeckShell s;
  s.id = need_int(field(fs, 0), line, "element ID");
  s.part = need_int(field(fs, 1), line, "part ID");
  if (s.id <= 0) refuse(f(), line, "element ID must be positive, got " + std::to_string(s.id));
  for (int k = 0; k < 4; ++k) s.nodes[k] = need_int(field(fs, 2 + k), line, "node ID", k == 3);
  for (int k = 0; k < 3; ++k)
    if (s.nodes[k] <= 0) refuse(f(), line, "element " + std::to_string(s.id) + " has no node " + std::to_string(k + 1));
  s.count = (s.nodes[3] == 0 || s.nodes[3] == s.nodes[2]) ? 3 : 4;
  if (s.count == 3) s.nodes[3] = 0;
  s.file = file, s.line = line;
  s.style = comma ? FieldStyle::Free : style;
  d().shells.push_back(s);
  pending = extra_cards;
}

void LsReader::part(std::string_view text, int line) {
  if (part_state == 0) {
    part_title = std::string(trim(text));
    part_state = 1;
    return;
  }
  if (part_state != 1) return;
  const auto& fs = fields(text, 1, widths(style).general, widths(style).general);
  DeckPart p;
  p.id = need_int(field(fs, 0), line, "part ID");
  p.name = part_title;
  d().parts.push_back(p);
  part_state = plain_part ? 0 : 2;
}

void LsReader::set_line(std::string_view text, int line) {
  DeckSet& s = d().sets[set];
  if (set_state == 0) {
    s.name = std::string(trim(text));
    set_state = 1;
    return;
  }
  const size_t w = widths(style).general;
  if (set_state == 1) {
    s.id = need_int(field(fields(text, 1, w, w), 0), line, "set ID");
    set_state = 2;
    s.data_begin = line + 1;
    s.data_end = line + 1;
    return;
  }
  const auto& fs = fields(text, 8, w, w);
  if (text.find(',') != std::string_view::npos) s.style = FieldStyle::Free;
  std::vector<long long> ids;
  for (const auto& x : fs) {
    if (trim(x).empty()) continue;
    ids.push_back(need_int(x, line, "set member"));
  }
  if (s.generate) {
    if (ids.size() % 2) refuse(f(), line, "a GENERATE range needs a first and a last ID");
    for (size_t k = 0; k < ids.size(); k += 2) {
      if (ids[k] <= 0 || ids[k + 1] < ids[k] || ids[k + 1] - ids[k] >= kMaxGenerated - (long long)s.members.size())
        refuse(f(), line, "bad GENERATE range " + std::to_string(ids[k]) + " to " + std::to_string(ids[k + 1]));
      s.members.reserve(s.members.size() + size_t(ids[k + 1] - ids[k] + 1));
      for (long long i = ids[k]; i <= ids[k + 1]; ++i) s.members.push_back(i);
    }
  } else {
    for (long long id : ids)
      if (id > 0) s.members.push_back(id);  // 0 is an empty field
  }
  s.data_end = line + 1;
}

void LsReader::run() {
  const int n = f().lines();
  for (int i = 0; i < n; ++i) {
    const std::string_view text = line_of(f(), i);
    if (!text.empty() && text[0] == '$') continue;
    if (!text.empty() && text[0] == '*') {
      keyword(text, i);
      continue;
    }
    // A blank line is no data, but where a *PART's title is due it is that title (left blank).
    if (trim(text).empty() && !(ctx == Ctx::Part && part_state == 0)) continue;
    switch (ctx) {
      case Ctx::Node: node(text, i); break;
      case Ctx::Shell: shell(text, i); break;
      case Ctx::Part: part(text, i); break;
      case Ctx::Set: set_line(text, i); break;
      case Ctx::Include: {
        const int inc = r.include(file, i, std::string(trim(text)));
        ++r.depth;
        LsReader sub(r, inc, global);
        sub.run();
        --r.depth;
        break;
      }
      case Ctx::OtherElement: {
        long long id;
        const std::string_view first = text.find(',') != std::string_view::npos ? split_commas(text)[0]
                                                                                 : column(text, 0, shell_width(style));
        if (parse_int(first, id) && id > d().max_element_id) d().max_element_id = id;
        break;
      }
      default: break;
    }
  }
  if (pending > 0 && !d().shells.empty()) refuse(f(), n, "the last shell element's cards are incomplete");
  if (set >= 0 && d().sets[set].data_end < d().sets[set].data_begin) d().sets[set].data_end = d().sets[set].data_begin;
}

std::string real_field(double x, size_t w) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%*.*e", int(w), int(w) - 8, x);
  return buf;
}

std::string int_field(long long x, size_t w) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%*lld", int(w), x);
  return buf;
}

bool fits(long long x, size_t w) { return std::to_string(x).size() <= w; }

}  // namespace

void read_lsdyna(Reader& r, int file) {
  LsReader reader(r, file, FieldStyle::Fixed);
  reader.run();
}

std::string lsdyna_node(const DeckNode& n, FieldStyle style, const std::string& eol) {
  const Widths w = widths(style);
  if (style == FieldStyle::Free || !fits(n.id, w.id)) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "%lld,%.17g,%.17g,%.17g", n.id, n.xyz.x(), n.xyz.y(), n.xyz.z());
    return buf + eol;
  }
  std::string out = int_field(n.id, w.id);
  for (int k = 0; k < 3; ++k) out += real_field(n.xyz[k], w.real);
  return out + eol;
}

std::string lsdyna_shell(const DeckShell& s, FieldStyle style, const std::string& eol) {
  const size_t w = shell_width(style);
  const long long v[6] = {s.id, s.part, s.nodes[0], s.nodes[1], s.nodes[2], s.count == 4 ? s.nodes[3] : s.nodes[2]};
  bool ok = style != FieldStyle::Free;
  for (long long x : v) ok = ok && fits(x, w);
  std::string out;
  for (int k = 0; k < 6; ++k) out += ok ? int_field(v[k], w) : (k ? "," : "") + std::to_string(v[k]);
  return out + eol;
}

std::string lsdyna_members(const std::vector<long long>& ids, FieldStyle style, const std::string& eol) {
  const size_t w = widths(style).general;
  bool fixed = style != FieldStyle::Free;
  for (long long x : ids) fixed = fixed && fits(x, w);
  std::string out;
  for (size_t k = 0; k < ids.size(); k += 8) {
    const size_t end = std::min(ids.size(), k + 8);
    for (size_t j = k; j < end; ++j) out += fixed ? int_field(ids[j], w) : (j > k ? "," : "") + std::to_string(ids[j]);
    if (!fixed && end == k + 1) out += ',';  // a line without a comma would be read in fixed fields
    out += eol;
  }
  return out;
}

}  // namespace meshround::decktext
