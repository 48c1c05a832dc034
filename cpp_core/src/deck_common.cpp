// What the three deck readers share: lines and fields, numbers, includes, and the deck-wide checks
// (unique IDs, every shell's nodes defined).
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstring>
#include <cmath>
#include <cstdio>

#include "deck_text.h"

namespace meshround {
namespace decktext {

namespace {
constexpr int kMaxIncludeDepth = 16;  // deeper nesting is taken for a cycle and refused
}

DeckFile make_file(const std::string& path, std::string text) {
  DeckFile f;
  f.path = path;
  f.text = std::move(text);
  f.line_start.reserve(f.text.size() / 40 + 2);
  f.line_start.push_back(0);
  const char* base = f.text.data();
  const char* end = base + f.text.size();
  for (const char* p = base; p < end;) {
    const char* nl = static_cast<const char*>(std::memchr(p, '\n', size_t(end - p)));
    if (!nl) break;
    p = nl + 1;
    f.line_start.push_back(size_t(p - base));
  }
  if (f.line_start.back() != f.text.size()) f.line_start.push_back(f.text.size());  // last line without an end
  if (f.line_start.size() > 1 && f.line_start[1] >= 2 && f.text[f.line_start[1] - 2] == '\r') f.eol = "\r\n";
  return f;
}

std::string_view line_of(const DeckFile& f, int i) {
  size_t a = f.line_start[i], b = f.line_start[i + 1];
  while (b > a && (f.text[b - 1] == '\n' || f.text[b - 1] == '\r')) --b;
  return std::string_view(f.text.data() + a, b - a);
}

void refuse(const DeckFile& f, int line, const std::string& reason) {
  throw RoundingError(ErrorCode::InvalidInput, f.path + ":" + std::to_string(line + 1) + ": " + reason);
}

std::string upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = char(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

bool starts_with_ci(std::string_view s, std::string_view prefix) {
  if (s.size() < prefix.size()) return false;
  for (size_t i = 0; i < prefix.size(); ++i)
    if (std::toupper(static_cast<unsigned char>(s[i])) != std::toupper(static_cast<unsigned char>(prefix[i]))) return false;
  return true;
}

std::string_view column(std::string_view line, size_t start, size_t width) {
  if (start >= line.size()) return {};
  return line.substr(start, std::min(width, line.size() - start));
}

void split_commas(std::string_view line, std::vector<std::string_view>& out) {
  out.clear();
  size_t a = 0;
  for (;;) {
    size_t c = line.find(',', a);
    out.push_back(trim(line.substr(a, c == std::string_view::npos ? std::string_view::npos : c - a)));
    if (c == std::string_view::npos) break;
    a = c + 1;
  }
}

std::vector<std::string_view> split_commas(std::string_view line) {
  std::vector<std::string_view> out;
  split_commas(line, out);
  return out;
}

bool parse_int(std::string_view s, long long& out, bool blank_ok, long long blank) {
  s = trim(s);
  if (s.empty()) {
    out = blank;
    return blank_ok;
  }
  if (s[0] == '+') s.remove_prefix(1);
  // The usual field: up to 18 digits (no overflow), optionally after a minus, read here.
  const size_t sign = !s.empty() && s[0] == '-' ? 1 : 0;
  if (s.size() > sign && s.size() - sign <= 18) {
    long long v = 0;
    size_t i = sign;
    for (; i < s.size() && s[i] >= '0' && s[i] <= '9'; ++i) v = v * 10 + (s[i] - '0');
    if (i == s.size()) {
      out = sign ? -v : v;
      return true;
    }
  }
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && p == s.data() + s.size();
}

bool parse_real(std::string_view s, double& out, bool nastran) {
  s = trim(s);
  if (s.empty()) {
    out = 0.0;
    return true;
  }
  // The usual field (no D exponent, no implied one) is read in place.
  bool plain = !nastran;
  for (size_t i = 0; plain && i < s.size(); ++i) plain = s[i] != 'd' && s[i] != 'D' && s[i] != ' ';
  if (plain) {
    const char* b = s.data() + (s[0] == '+' ? 1 : 0);
    auto [p, ec] = std::from_chars(b, s.data() + s.size(), out);
    return ec == std::errc() && p == s.data() + s.size() && std::isfinite(out);
  }
  // At most 40 characters, each of which may gain an implied 'e' before it: 80 at most.
  constexpr size_t kMaxChars = 40;
  char buf[2 * kMaxChars];
  if (s.size() > kMaxChars) return false;
  size_t n = 0;
  for (size_t i = 0; i < s.size(); ++i) {
    char c = s[i];
    if (c == ' ') return false;
    if (c == 'd' || c == 'D') c = 'e';
    // Nastran's implied exponent: a sign after a digit or point, not after an E ("1.5-3" is 1.5e-3).
    if (nastran && (c == '+' || c == '-') && i > 0 && n > 0 && buf[n - 1] != 'e' && buf[n - 1] != 'E') buf[n++] = 'e';
    buf[n++] = c;
  }
  const char* b = buf;
  if (*b == '+') ++b;
  auto [p, ec] = std::from_chars(b, buf + n, out);
  return ec == std::errc() && p == buf + n && std::isfinite(out);
}

std::string folder_of(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

std::string resolve(const std::string& folder, const std::string& name) {
  if (!name.empty() && name[0] == '/') return name;
  return folder + name;
}

int Reader::include(int from, int line, const std::string& name) {
  const DeckFile& parent = deck.files[from];
  if (name.empty()) refuse(parent, line, "include without a file name");
  if (depth >= kMaxIncludeDepth) refuse(parent, line, "includes nested more than 16 deep (a cycle?): '" + name + "'");
  const std::string path = resolve(folder_of(parent.path), name);
  std::string text;
  if (!load || !load(path, text)) refuse(parent, line, "cannot read the included file '" + path + "'");
  deck.files.push_back(make_file(path, std::move(text)));
  return int(deck.files.size()) - 1;
}

}  // namespace decktext

using namespace decktext;

namespace {

std::string lower_extension(const std::string& path) {
  const size_t dot = path.find_last_of('.');
  const size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

std::string where(const Deck& d, int file, int line) { return d.files[file].path + ":" + std::to_string(line + 1); }

// Unique node and shell IDs (Deck::node_by_id, shell_by_id); every shell's nodes defined (node_index
// filled); parts referenced by shells listed (LS-DYNA and Nastran decks may define a part in a file the
// reader does not see).
void check_and_index(Deck& d) {
  std::vector<long long> ids(d.nodes.size());
  for (size_t i = 0; i < d.nodes.size(); ++i) ids[i] = d.nodes[i].id, d.max_node_id = std::max(d.max_node_id, ids[i]);
  if (auto [i, j] = d.node_by_id.build(ids); i >= 0) {
    const DeckNode &n = d.nodes[i], &o = d.nodes[j];
    refuse(d.files[n.file], n.line, "node " + std::to_string(n.id) + " is defined twice (also at " + where(d, o.file, o.line) + ")");
  }
  ids.resize(d.shells.size());
  for (size_t i = 0; i < d.shells.size(); ++i) ids[i] = d.shells[i].id;
  // Shells in order: a twice-defined ID is named before a missing node of a later shell, as before.
  const auto [twice, first] = d.shell_by_id.build(ids);
  for (int i = 0; i < int(d.shells.size()); ++i) {
    DeckShell& s = d.shells[i];
    if (i == twice) {
      const DeckShell& o = d.shells[first];
      refuse(d.files[s.file], s.line, "element " + std::to_string(s.id) + " is defined twice (also at " + where(d, o.file, o.line) + ")");
    }
    d.max_element_id = std::max(d.max_element_id, s.id);
    for (int k = 0; k < 4; ++k) {
      s.node_index[k] = -1;
      if (k >= s.count) continue;
      const int n = d.node_by_id.find(s.nodes[k]);
      if (n < 0)
        refuse(d.files[s.file], s.line, "element " + std::to_string(s.id) + " refers to node " + std::to_string(s.nodes[k]) + ", which the deck does not define");
      s.node_index[k] = n;
    }
  }
  std::vector<long long> known;
  for (const DeckPart& p : d.parts) known.push_back(p.id);
  std::sort(known.begin(), known.end());
  for (const DeckShell& s : d.shells)
    if (!std::binary_search(known.begin(), known.end(), s.part)) {
      d.parts.push_back({s.part, ""});
      known.insert(std::upper_bound(known.begin(), known.end(), s.part), s.part);
    }
}

}  // namespace

std::pair<int, int> IdIndex::build(const std::vector<long long>& ids) {
  count_ = ids.size();
  table_.clear(), sorted_.clear();
  if (ids.empty()) return {-1, -1};
  const auto [lo, hi] = std::minmax_element(ids.begin(), ids.end());
  const unsigned long long span = static_cast<unsigned long long>(*hi) - static_cast<unsigned long long>(*lo);
  if (span <= 2 * ids.size() + 1024) {  // dense: at most ~2 slots per record
    first_ = *lo;
    table_.assign(span + 1, -1);
    for (int i = 0; i < int(ids.size()); ++i) {
      int& slot = table_[size_t(ids[i] - first_)];
      if (slot >= 0) return {i, slot};
      slot = i;
    }
    return {-1, -1};
  }
  sorted_.resize(ids.size());
  for (int i = 0; i < int(ids.size()); ++i) sorted_[i] = {ids[i], i};
  std::sort(sorted_.begin(), sorted_.end());
  // Within an ID the records are in order, so the smallest record that is not its ID's first is a second
  // occurrence, and the one before it in sorted_ that ID's first.
  std::pair<int, int> twice{-1, -1};
  for (size_t k = 1; k < sorted_.size(); ++k)
    if (sorted_[k].first == sorted_[k - 1].first && (twice.first < 0 || sorted_[k].second < twice.first))
      twice = {sorted_[k].second, sorted_[k - 1].second};
  return twice;
}

int IdIndex::find(long long id) const {
  if (!sorted_.empty()) {
    auto it = std::lower_bound(sorted_.begin(), sorted_.end(), std::make_pair(id, -1));
    return it != sorted_.end() && it->first == id ? it->second : -1;
  }
  if (table_.empty() || id < first_ || static_cast<unsigned long long>(id - first_) >= table_.size()) return -1;
  return table_[size_t(id - first_)];
}

DeckFormat deck_format_for(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == "k" || ext == "key" || ext == "dyn") return DeckFormat::LsDyna;
  if (ext == "bdf" || ext == "nas" || ext == "dat") return DeckFormat::Nastran;
  if (ext == "inp") return DeckFormat::Abaqus;
  throw RoundingError(ErrorCode::InvalidInput, "'" + path + "' is not a solver deck by its extension (.k .key .dyn: LS-DYNA, "
                                               ".bdf .nas .dat: Nastran, .inp: Abaqus)");
}

const char* deck_format_name(DeckFormat format) {
  switch (format) {
    case DeckFormat::LsDyna: return "lsdyna";
    case DeckFormat::Nastran: return "nastran";
    default: return "abaqus";
  }
}

Deck parse_deck(const std::string& path, std::string text, DeckFormat format, const DeckLoader& load) {
  Deck d;
  d.format = format;
  d.files.push_back(make_file(path, std::move(text)));
  // At most one record per line: reserved (address space only; pages are taken as records fill them), so
  // the vectors are not copied as they grow -- each copy touches fresh memory, and page faults were a
  // third of a big deck's read.
  d.nodes.reserve(size_t(d.files[0].lines()));
  d.shells.reserve(size_t(d.files[0].lines()));
  Reader r{d, load};
  switch (format) {
    case DeckFormat::LsDyna: read_lsdyna(r, 0); break;
    case DeckFormat::Nastran: read_nastran(r, 0); break;
    case DeckFormat::Abaqus: read_abaqus(r, 0); break;
  }
  check_and_index(d);
  return d;
}

namespace {
bool load_file(const std::string& path, std::string& text) {
  std::FILE* in = std::fopen(path.c_str(), "rb");
  if (!in) return false;
  text.clear();
  bool ok = std::fseek(in, 0, SEEK_END) == 0;
  const long size = ok ? std::ftell(in) : -1;
  if (size > 0 && std::fseek(in, 0, SEEK_SET) == 0) {  // a regular file: read at once
    text.resize(size_t(size));
    text.resize(std::fread(text.data(), 1, text.size(), in));
  }
  char buf[1 << 16];  // what is left (a file that grew, or one that cannot seek: a pipe)
  if (size < 0) std::clearerr(in);
  for (size_t n; (n = std::fread(buf, 1, sizeof buf, in)) > 0;) text.append(buf, n);
  ok = !std::ferror(in);
  std::fclose(in);
  return ok;
}
}  // namespace

Deck read_deck(const std::string& path) {
  const DeckFormat format = deck_format_for(path);
  std::string text;
  if (!load_file(path, text)) throw RoundingError(ErrorCode::InvalidInput, "cannot read '" + path + "'");
  return parse_deck(path, std::move(text), format, load_file);
}

}  // namespace meshround
