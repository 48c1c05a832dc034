// Abaqus input files: *NODE, *ELEMENT with a 3- or 4-node shell, membrane, surface or rigid TYPE (S3,
// S3R, S4, S4R, R3D3, R3D4, ...), *NSET and *ELSET (GENERATE too), *INCLUDE, INPUT=<file> (read in place,
// as Abaqus does: its data lines continue the keyword before it). Everything else is kept as it is.
#include <cstdio>
#include <map>

#include "deck_text.h"

namespace meshround::decktext {

namespace {

int shell_nodes(const std::string& type) {
  static const std::map<std::string, int> known = {
      {"S3", 3},   {"S3R", 3},   {"S3RS", 3},  {"STRI3", 3},  {"M3D3", 3},  {"R3D3", 3},  {"SFM3D3", 3},
      {"S4", 4},   {"S4R", 4},   {"S4RS", 4},  {"S4R5", 4},   {"M3D4", 4},  {"M3D4R", 4}, {"R3D4", 4},
      {"SFM3D4", 4}, {"SFM3D4R", 4}};
  auto it = known.find(type);
  return it == known.end() ? 0 : it->second;
}

enum class Ctx { None, Node, Shell, OtherElement, Set };

struct Keyword {
  std::string name;                           // upper case, spaces removed
  std::map<std::string, std::string> params;  // upper-case key -> value as written (trimmed)
};

Keyword parse_keyword(std::string_view line) {
  Keyword k;
  const auto toks = split_commas(line.substr(1));
  for (char c : toks[0])
    if (c != ' ') k.name += char(std::toupper(static_cast<unsigned char>(c)));
  for (size_t i = 1; i < toks.size(); ++i) {
    const size_t eq = toks[i].find('=');
    std::string key = upper(trim(toks[i].substr(0, eq)));
    k.params[key] = eq == std::string_view::npos ? "" : std::string(trim(toks[i].substr(eq + 1)));
  }
  return k;
}

// The keyword state, shared with an included file (its data lines continue the keyword before it).
struct State {
  Ctx ctx = Ctx::None;
  std::string type;  // *ELEMENT TYPE
  int count = 0;     // its nodes
  long long part = 0;
  int set = -1;
  std::vector<std::string_view> pending;  // an element record continued on the next line (trailing ',')
  int pending_line = -1, pending_file = -1;
};

struct AbqReader {
  Reader& r;
  int file;
  State st;

  const DeckFile& f() const { return r.deck.files[file]; }
  Deck& d() { return r.deck; }

  long long need_int(std::string_view s, int line, const char* what) {
    long long v;
    if (!parse_int(s, v)) refuse(f(), line, std::string("bad ") + what + " '" + std::string(s) + "'");
    return v;
  }

  long long part_named(const std::string& name) {
    const std::string key = upper(name);
    for (const DeckPart& p : d().parts)
      if (upper(p.name) == key) return p.id;
    d().parts.push_back({(long long)d().parts.size() + 1, name});
    return d().parts.back().id;
  }

  void keyword(std::string_view text, int line);
  void node(std::string_view text, int line);
  void element(std::string_view text, int line);
  void set_line(std::string_view text, int line);
  void run();
};

void AbqReader::keyword(std::string_view text, int line) {
  if (!st.pending.empty()) refuse(f(), st.pending_line, "an element record ends with ',' but no line continues it");
  const Keyword k = parse_keyword(text);
  if (k.name == "INCLUDE") {
    auto in = k.params.find("INPUT");
    if (in == k.params.end()) refuse(f(), line, "*INCLUDE without INPUT=<file>");
    std::string name = in->second;
    if (name.size() >= 2 && (name[0] == '"' || name[0] == '\'')) name = name.substr(1, name.size() - 2);
    const int inc = r.include(file, line, name);
    ++r.depth;
    AbqReader sub{r, inc, st};
    sub.run();
    --r.depth;
    st = sub.st;
    return;
  }
  st.ctx = Ctx::None;
  st.set = -1;
  if (k.name == "NODE") {
    st.ctx = Ctx::Node;
  } else if (k.name == "ELEMENT") {
    auto t = k.params.find("TYPE");
    if (t == k.params.end()) refuse(f(), line, "*ELEMENT without TYPE=");
    st.type = upper(t->second);
    st.count = shell_nodes(st.type);
    st.ctx = st.count ? Ctx::Shell : Ctx::OtherElement;
    auto e = k.params.find("ELSET");
    st.part = part_named(e == k.params.end() ? "" : e->second);
  } else if ((k.name == "NSET" || k.name == "ELSET") && !k.params.count("INSTANCE")) {
    DeckSet s;
    s.of_nodes = k.name == "NSET";
    auto nm = k.params.find(s.of_nodes ? "NSET" : "ELSET");
    if (nm == k.params.end()) refuse(f(), line, "*" + k.name + " without " + k.name + "=<name>");
    s.name = nm->second;
    s.generate = k.params.count("GENERATE") > 0;
    s.file = file, s.keyword_line = line, s.data_begin = s.data_end = line + 1, s.style = FieldStyle::Free;
    d().sets.push_back(s);
    st.ctx = Ctx::Set;
    st.set = int(d().sets.size()) - 1;
  }
}

void AbqReader::node(std::string_view text, int line) {
  const auto fs = split_commas(text);
  DeckNode n;
  n.id = need_int(fs[0], line, "node ID");
  if (n.id <= 0) refuse(f(), line, "node ID must be positive, got " + std::to_string(n.id));
  if (fs.size() < 2) refuse(f(), line, "node " + std::to_string(n.id) + " has no coordinates");
  for (int k = 0; k < 3; ++k) {
    const std::string_view c = k + 1 < int(fs.size()) ? fs[k + 1] : std::string_view();
    if (!parse_real(c, n.xyz[k])) refuse(f(), line, "bad coordinate '" + std::string(c) + "'");
  }
  n.file = file, n.line = line, n.style = FieldStyle::Free;
  d().nodes.push_back(n);
}

void AbqReader::element(std::string_view text, int line) {
  auto fs = split_commas(text);
  const bool continues = !trim(text).empty() && trim(text).back() == ',';
  if (continues) fs.pop_back();  // the empty field after the trailing comma
  if (st.pending.empty()) st.pending_line = line, st.pending_file = file;
  else if (st.pending_file != file) refuse(f(), line, "an element record continued across files");
  st.pending.insert(st.pending.end(), fs.begin(), fs.end());
  if (continues) return;
  const int first = st.pending_line;
  std::vector<std::string_view> all;
  all.swap(st.pending);
  const long long id = need_int(all[0], first, "element ID");
  if (id <= 0) refuse(f(), first, "element ID must be positive, got " + std::to_string(id));
  if (st.ctx == Ctx::OtherElement) {
    d().max_element_id = std::max(d().max_element_id, id);
    return;
  }
  if (int(all.size()) != st.count + 1)
    refuse(f(), first, "element " + std::to_string(id) + " of TYPE=" + st.type + " needs " + std::to_string(st.count) + " nodes, has " + std::to_string(all.size() - 1));
  DeckShell s;
  s.id = id, s.part = st.part, s.count = st.count, s.type = st.type;
  for (int k = 0; k < st.count; ++k) {
    s.nodes[k] = need_int(all[k + 1], first, "node ID");
    if (s.nodes[k] <= 0) refuse(f(), first, "element " + std::to_string(id) + ": node ID must be positive");
  }
  s.file = file, s.line = first, s.lines = line - first + 1, s.style = FieldStyle::Free;
  d().shells.push_back(s);
}

void AbqReader::set_line(std::string_view text, int line) {
  DeckSet& s = d().sets[st.set];
  std::vector<long long> ids;
  for (std::string_view x : split_commas(text)) {
    if (x.empty()) continue;
    long long v;
    if (parse_int(x, v)) ids.push_back(v);
    else if (s.generate) refuse(f(), line, "bad GENERATE value '" + std::string(x) + "'");
    else s.named_members.push_back(std::string(x));
  }
  if (s.generate) {
    if (ids.size() < 2 || ids.size() > 3) refuse(f(), line, "GENERATE needs first, last[, step]");
    const long long step = ids.size() == 3 ? ids[2] : 1;
    if (ids[0] <= 0 || ids[1] < ids[0] || step <= 0 || (ids[1] - ids[0]) / step >= kMaxGenerated - (long long)s.members.size())
      refuse(f(), line, "bad GENERATE range " + std::to_string(ids[0]) + ", " + std::to_string(ids[1]) + ", " + std::to_string(step));
    s.members.reserve(s.members.size() + size_t((ids[1] - ids[0]) / step + 1));
    for (long long i = ids[0]; i <= ids[1]; i += step) s.members.push_back(i);
  } else {
    s.members.insert(s.members.end(), ids.begin(), ids.end());
  }
  s.data_end = line + 1;
}

void AbqReader::run() {
  const int n = f().lines();
  for (int i = 0; i < n; ++i) {
    const std::string_view text = line_of(f(), i);
    if (text.size() >= 2 && text[0] == '*' && text[1] == '*') continue;
    if (!text.empty() && text[0] == '*') {
      keyword(text, i);
      continue;
    }
    if (trim(text).empty()) continue;
    switch (st.ctx) {
      case Ctx::Node: node(text, i); break;
      case Ctx::Shell:
      case Ctx::OtherElement: element(text, i); break;
      case Ctx::Set:
        if (d().sets[st.set].file != file) break;
        set_line(text, i);
        break;
      default: break;
    }
  }
  if (!st.pending.empty() && r.depth == 0) refuse(f(), st.pending_line, "an element record ends with ',' but no line continues it");
}

}  // namespace

void read_abaqus(Reader& r, int file) {
  AbqReader reader{r, file, State()};
  reader.run();
}

std::string abaqus_node(const DeckNode& n, const std::string& eol) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "%lld, %.15g, %.15g, %.15g", n.id, n.xyz.x(), n.xyz.y(), n.xyz.z());
  return buf + eol;
}

std::string abaqus_shell(const DeckShell& s, const std::string& eol) {
  std::string out = std::to_string(s.id);
  for (int k = 0; k < s.count; ++k) out += ", " + std::to_string(s.nodes[k]);
  return out + eol;
}

std::string abaqus_members(const std::vector<long long>& ids, const std::vector<std::string>& names, const std::string& eol) {
  std::vector<std::string> all(names);
  for (long long x : ids) all.push_back(std::to_string(x));
  std::string out;
  for (size_t k = 0; k < all.size(); ++k) {
    out += all[k];
    out += (k + 1 == all.size() || k % 16 == 15) ? eol : ", ";
  }
  return out;
}

}  // namespace meshround::decktext
