// Private to the deck readers and writer: lines, fields, numbers, errors, and the per-format entry points.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "meshround/deck.h"

namespace meshround::decktext {

// Members one set's GENERATE ranges may expand to; a deck asking for more is refused (a typo in a range
// would otherwise take the memory and time of a huge set).
constexpr long long kMaxGenerated = 10'000'000;

// Splits a file's text into lines (DeckFile::line_start, eol).
DeckFile make_file(const std::string& path, std::string text);
// Line i without its line end.
std::string_view line_of(const DeckFile& f, int i);

// invalid_input "<file>:<line>: <reason>" (line is 0-based here, printed 1-based).
[[noreturn]] void refuse(const DeckFile& f, int line, const std::string& reason);

inline std::string_view trim(std::string_view s) {  // inline: called for every field
  const char* a = s.data();
  const char* b = a + s.size();
  while (a < b && (*a == ' ' || *a == '\t')) ++a;
  while (b > a && (b[-1] == ' ' || b[-1] == '\t')) --b;
  return std::string_view(a, size_t(b - a));
}
std::string upper(std::string_view s);
bool starts_with_ci(std::string_view s, std::string_view prefix);  // case-insensitive
// Columns [start, start + width) of a line (clipped to it, possibly empty).
std::string_view column(std::string_view line, size_t start, size_t width);
// Comma-separated fields (each trimmed).
std::vector<std::string_view> split_commas(std::string_view line);
void split_commas(std::string_view line, std::vector<std::string_view>& out);  // into out (no allocation once grown)

// An integer field; blank is `blank` when allowed (blank_ok), else false. Rejects anything else.
bool parse_int(std::string_view s, long long& out, bool blank_ok = false, long long blank = 0);
// A real field: plain, Fortran D exponent, and (nastran) implied exponent "1.5-3"; blank is 0.
bool parse_real(std::string_view s, double& out, bool nastran = false);

// The folder part of a path ("" for none), and a path resolved against a folder.
std::string folder_of(const std::string& path);
std::string resolve(const std::string& folder, const std::string& name);

// Shared by the three readers: the deck under construction and its include machinery.
struct Reader {
  Deck& deck;
  const DeckLoader& load;
  int depth = 0;
  // Loads an include named on line `line` of file `from`; returns its file index (refused if missing or
  // nested too deep).
  int include(int from, int line, const std::string& name);
};

// Nastran SET1 / SET3 cards, read while the bulk data is (deck_nastran_sets.cpp) and resolved to grid or
// element sets once the whole deck is (a SET1 does not say which it holds: DeckSet::kind_known).
struct NastranSets {
  struct Item {
    long long first, last;  // an ID (first == last) or a THRU range
    bool range;
  };
  struct Pending {
    int set;  // index into Deck::sets
    std::vector<Item> items;
  };
  std::vector<Pending> pending;
  std::vector<long long> other_elements;  // IDs of element cards other than CTRIA3 / CQUAD4 (CBAR, RBE2, ...)
  std::vector<long long> grid_set_refs;   // SIDs that SPLINE1/2/4/5 name as their SETG: sets of grids
  // One card: `fields` are its data fields (field 2 on), `field_line` the line of each, `overflow` a
  // free-field line with more than 10 fields (-1: none). Refuses a malformed card naming its line.
  void card(Deck& d, int file, int first, int last, const std::string& name, FieldStyle style,
            const std::vector<std::string_view>& fields, const std::vector<int>& field_line, int overflow);
  void resolve(Deck& d) const;
};

void read_lsdyna(Reader& r, int file);
void read_nastran(Reader& r, int file);
void read_abaqus(Reader& r, int file);

// One record's text (lines joined with eol, ending with eol) in a format's style.
std::string lsdyna_node(const DeckNode& n, FieldStyle style, const std::string& eol);
std::string lsdyna_shell(const DeckShell& s, FieldStyle style, const std::string& eol);
std::string lsdyna_members(const std::vector<long long>& ids, FieldStyle style, const std::string& eol);
std::string nastran_node(const DeckNode& n, FieldStyle style, const std::string& eol);
std::string nastran_shell(const DeckShell& s, FieldStyle style, const std::string& eol);
std::string nastran_set(const DeckSet& s, const std::vector<long long>& ids, const std::string& eol);
std::string abaqus_node(const DeckNode& n, const std::string& eol);
std::string abaqus_shell(const DeckShell& s, const std::string& eol);
std::string abaqus_members(const std::vector<long long>& ids, const std::vector<std::string>& names,
                           const std::string& eol);

}  // namespace meshround::decktext
