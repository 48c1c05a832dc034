// write_deck(): the deck's files with edits applied; every line an edit does not name is copied byte for
// byte (deck.h).
#include <algorithm>
#include <map>
#include <unordered_set>

#include "deck_text.h"

namespace meshround {

using namespace decktext;

namespace {

[[noreturn]] void bad_edit(const std::string& why) { throw RoundingError(ErrorCode::InvalidInput, "deck edit: " + why); }

// What happens to each line of one file.
struct FileOut {
  std::vector<char> drop;
  std::map<int, std::string> replace;  // line -> text written instead (with its line end)
  std::map<int, std::string> after;    // line -> text written after it
};

// The deck's index of `records` by ID (parse_deck makes it), or one made here for a deck made otherwise.
template <class Record>
const IdIndex& index_of(const std::vector<Record>& records, const IdIndex& made, IdIndex& local) {
  if (made.size() == records.size()) return made;
  std::vector<long long> ids;
  ids.reserve(records.size());
  for (const Record& r : records) ids.push_back(r.id);
  local.build(ids);
  return local;
}

// Marks the records of `ids` gone (by record index) and their lines dropped.
template <class Record>
std::vector<char> drop_records(const Deck& d, const std::vector<Record>& records, const IdIndex& at,
                               const std::vector<long long>& ids, const char* what, std::vector<FileOut>& out) {
  std::vector<char> gone(records.size(), 0);
  for (long long id : ids) {
    const int i = at.find(id);
    if (i < 0) bad_edit(std::string("no ") + what + " " + std::to_string(id) + " to remove");
    if (gone[i]) continue;
    gone[i] = 1;
    const Record& r = records[i];
    for (int k = 0; k < r.lines; ++k) out[r.file].drop[r.line + k] = 1;
  }
  return gone;
}

std::string node_text(const Deck& d, const DeckNode& n, FieldStyle style, const std::string& eol) {
  switch (d.format) {
    case DeckFormat::LsDyna: return lsdyna_node(n, style, eol);
    case DeckFormat::Nastran: return nastran_node(n, style, eol);
    default: return abaqus_node(n, eol);
  }
}

// An Abaqus element type for a new shell of `count` nodes in `part`: the type of a shell of that part with
// as many nodes, else the part's type turned to that count (S4R <-> S3R, S4 <-> S3, R3D4 <-> R3D3, ...).
std::string abaqus_type(const Deck& d, long long part, int count) {
  std::string other;
  for (const DeckShell& s : d.shells) {
    if (s.part != part) continue;
    if (s.count == count) return s.type;
    if (other.empty()) other = s.type;
  }
  if (other.empty()) bad_edit("part " + std::to_string(part) + " has no shell elements to take an element type from");
  static const std::pair<const char*, const char*> pairs[] = {{"S3R", "S4R"}, {"S3", "S4"}, {"R3D3", "R3D4"}, {"M3D3", "M3D4"},
                                                              {"S3RS", "S4RS"}, {"SFM3D3", "SFM3D4"}, {"STRI3", "S4"}};
  for (const auto& [tri, quad] : pairs) {
    if (count == 3 && other == quad) return tri;
    if (count == 4 && other == tri) return quad;
  }
  return count == 3 ? "S3" : "S4";
}

std::string shells_text(const Deck& d, const std::vector<DeckShell>& shells, FieldStyle style, const std::string& eol) {
  std::string out;
  if (d.format != DeckFormat::Abaqus) {
    for (const DeckShell& s : shells)
      out += d.format == DeckFormat::LsDyna ? lsdyna_shell(s, style, eol) : nastran_shell(s, style, eol);
    return out;
  }
  std::map<std::pair<long long, int>, std::vector<const DeckShell*>> blocks;  // (part, count) -> shells
  for (const DeckShell& s : shells) blocks[{s.part, s.count}].push_back(&s);
  for (const auto& [key, members] : blocks) {
    std::string name;
    bool known = false;
    for (const DeckPart& p : d.parts)
      if (p.id == key.first) name = p.name, known = true;
    if (!known) bad_edit("part " + std::to_string(key.first) + " is not in the deck");
    out += "*ELEMENT, TYPE=" + abaqus_type(d, key.first, key.second) + (name.empty() ? "" : ", ELSET=" + name) + eol;
    for (const DeckShell* s : members) out += abaqus_shell(*s, eol);
  }
  return out;
}

// The keyword line of a set that was GENERATE, now listing its members.
std::string without_generate(const Deck& d, const DeckSet& s) {
  const DeckFile& f = d.files[s.file];
  std::string line(line_of(f, s.keyword_line));
  if (d.format == DeckFormat::LsDyna) {
    const std::string up = upper(line);
    const size_t at = up.find("_GENERATE");
    if (at != std::string::npos) line.erase(at, 9);
    return line + f.eol;
  }
  std::string out;
  size_t a = 0;
  for (;;) {
    const size_t c = line.find(',', a);
    const std::string tok = line.substr(a, c == std::string::npos ? std::string::npos : c - a);
    if (upper(trim(tok)) != "GENERATE") out += (out.empty() ? "" : ",") + tok;
    if (c == std::string::npos) break;
    a = c + 1;
  }
  return out + f.eol;
}

void rewrite_sets(const Deck& d, const DeckEdits& e, std::vector<FileOut>& out) {
  for (const auto& [index, ids] : e.set_members) {
    if (index < 0 || index >= int(d.sets.size())) bad_edit("no set " + std::to_string(index));
    const DeckSet& s = d.sets[index];
    const DeckFile& f = d.files[s.file];
    for (long long id : ids)
      if (id <= 0) bad_edit("set " + std::to_string(index) + " is given the ID " + std::to_string(id) + " (IDs are positive)");
    const std::string text = d.format == DeckFormat::LsDyna    ? lsdyna_members(ids, s.style, f.eol)
                             : d.format == DeckFormat::Nastran ? nastran_set(s, ids, f.eol)
                                                               : abaqus_members(ids, s.named_members, f.eol);
    FileOut& o = out[s.file];
    if (s.data_end > s.data_begin) {
      o.replace[s.data_begin] = text;
      for (int l = s.data_begin + 1; l < s.data_end; ++l) o.drop[l] = 1;
    } else {
      o.after[s.data_begin - 1] += text;
    }
    if (s.generate) o.replace[s.keyword_line] = without_generate(d, s);
  }
}

// New IDs unused and positive; every element that stays or is new refers to nodes the deck will hold.
// gone_nodes / gone_shells: by record index.
void check_new_ids(const Deck& d, const DeckEdits& e, const IdIndex& node_at, const IdIndex& shell_at,
                   const std::vector<char>& gone_nodes, const std::vector<char>& gone_shells) {
  for (size_t i = 0; i < d.shells.size(); ++i) {
    const DeckShell& s = d.shells[i];
    if (gone_shells[i]) continue;
    for (int k = 0; k < s.count; ++k) {
      const int n = s.node_index[k] >= 0 ? s.node_index[k] : node_at.find(s.nodes[k]);
      if (n >= 0 && gone_nodes[n])
        bad_edit("node " + std::to_string(s.nodes[k]) + " is removed but element " + std::to_string(s.id) + " keeps it");
    }
  }
  std::unordered_set<long long> new_nodes, new_elements;
  for (const DeckNode& n : e.new_nodes) {
    if (n.id <= 0 || node_at.find(n.id) >= 0 || !new_nodes.insert(n.id).second)
      bad_edit("new node ID " + std::to_string(n.id) + " is in use or not positive");
    if (!n.xyz.allFinite()) bad_edit("new node " + std::to_string(n.id) + " has a non-finite coordinate");
  }
  for (const DeckShell& s : e.new_shells) {
    if (s.id <= 0 || shell_at.find(s.id) >= 0 || !new_elements.insert(s.id).second)
      bad_edit("new element ID " + std::to_string(s.id) + " is in use or not positive");
    if (s.count != 3 && s.count != 4) bad_edit("element " + std::to_string(s.id) + " must have 3 or 4 nodes");
    for (int k = 0; k < s.count; ++k) {
      const int n = node_at.find(s.nodes[k]);
      if (n >= 0 ? bool(gone_nodes[n]) : !new_nodes.count(s.nodes[k]))
        bad_edit("new element " + std::to_string(s.id) + " refers to node " + std::to_string(s.nodes[k]) + ", which the deck will not hold");
    }
  }
}

}  // namespace

std::vector<std::string> write_deck(const Deck& d, const DeckEdits& e) {
  std::vector<FileOut> out(d.files.size());
  for (size_t i = 0; i < d.files.size(); ++i) out[i].drop.assign(d.files[i].lines(), 0);
  IdIndex own_nodes, own_shells;
  const IdIndex& node_at = index_of(d.nodes, d.node_by_id, own_nodes);
  const IdIndex& shell_at = index_of(d.shells, d.shell_by_id, own_shells);
  const auto gone_nodes = drop_records(d, d.nodes, node_at, e.removed_nodes, "node", out);
  const auto gone_shells = drop_records(d, d.shells, shell_at, e.removed_shells, "element", out);
  check_new_ids(d, e, node_at, shell_at, gone_nodes, gone_shells);
  if (!e.new_nodes.empty()) {
    if (d.nodes.empty()) bad_edit("the deck has no node record to place new nodes after");
    const DeckNode& last = d.nodes.back();
    const std::string& eol = d.files[last.file].eol;
    std::string text = d.format == DeckFormat::Abaqus ? "*NODE" + eol : "";
    for (const DeckNode& n : e.new_nodes) text += node_text(d, n, last.style, eol);
    out[last.file].after[last.line + last.lines - 1] += text;
  }
  if (!e.new_shells.empty()) {
    if (d.shells.empty()) bad_edit("the deck has no shell element to place new elements after");
    const DeckShell& last = d.shells.back();
    out[last.file].after[last.line + last.lines - 1] += shells_text(d, e.new_shells, last.style, d.files[last.file].eol);
  }
  rewrite_sets(d, e, out);

  std::vector<std::string> texts(d.files.size());
  for (size_t i = 0; i < d.files.size(); ++i) {
    const DeckFile& f = d.files[i];
    const FileOut& o = out[i];
    std::string& t = texts[i];
    t.reserve(f.text.size() + 64);
    auto rep = o.replace.begin();
    auto aft = o.after.begin();
    size_t run = 0;  // kept lines are copied in runs: text from `run` up to the line being looked at
    for (int l = 0; l < f.lines(); ++l) {
      const bool replaced = rep != o.replace.end() && rep->first == l;
      const bool inserted = aft != o.after.end() && aft->first == l;
      if (!replaced && !o.drop[l] && !inserted) continue;  // stays in the run
      t.append(f.text, run, f.line_start[l] - run);
      run = f.line_start[l + 1];
      if (replaced) {
        t += rep->second;
        ++rep;
      } else if (!o.drop[l]) {
        t.append(f.text, f.line_start[l], f.line_start[l + 1] - f.line_start[l]);
      }
      if (inserted) {
        if (!t.empty() && t.back() != '\n') t += f.eol;
        t += aft->second;
        ++aft;
      }
    }
    t.append(f.text, run, f.text.size() - run);
  }
  return texts;
}

}  // namespace meshround
