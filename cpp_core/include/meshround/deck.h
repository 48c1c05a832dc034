// Solver decks (LS-DYNA keyword, Nastran bulk data, Abaqus input) read and written losslessly.
//
// A Deck keeps every file's text byte for byte and indexes what a rounding needs: nodes, 3- and 4-node
// shell elements, parts and node/element sets, each with the file and lines it came from. write_deck()
// emits the files again with DeckEdits applied (records removed, records added, sets given new members);
// every other line comes out byte-identical, so a deck read and written without edits is the same bytes.
// Malformed records are refused with RoundingError(invalid_input) naming the file, the line and why.
#pragma once
#include <array>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "meshround/types.h"

namespace meshround {

enum class DeckFormat { LsDyna, Nastran, Abaqus };

// The format a file name's extension stands for: .k .key .dyn, .bdf .nas .dat, .inp (case-insensitive);
// throws invalid_input for any other extension.
DeckFormat deck_format_for(const std::string& path);
const char* deck_format_name(DeckFormat format);  // "lsdyna", "nastran", "abaqus"

// How a record's fields are laid out; new records are written in the style of their neighbours.
enum class FieldStyle {
  Fixed,  // LS-DYNA standard (i8 / e16 / 10-column cards), Nastran small field (8 columns)
  Long,   // LS-DYNA long (`+` suffix, *KEYWORD LONG=Y: 20 columns), Nastran large field (`*`, 16 columns)
  I10,    // LS-DYNA i10 (`%` suffix, *KEYWORD I10=Y): integers 10 columns wide
  Free,   // comma-separated (LS-DYNA free format, Nastran free field, Abaqus always)
};

struct DeckFile {
  std::string path;                // as given (the main file) or resolved (an include)
  std::string text;                // the file's bytes
  std::vector<size_t> line_start;  // line i is text[line_start[i], line_start[i+1]) with its line end
  std::string eol = "\n";          // the file's line end ("\r\n" when its first line has one)
  int lines() const { return int(line_start.size()) - 1; }
};

struct DeckNode {
  long long id = 0;
  Vec3 xyz = Vec3::Zero();
  int file = 0, line = 0, lines = 1;  // the record: lines [line, line + lines) of files[file]
  FieldStyle style = FieldStyle::Fixed;
};

struct DeckShell {
  long long id = 0;
  long long part = 0;  // LS-DYNA PID, Nastran PID, Abaqus: index+1 of the ELSET of its *ELEMENT block
  int count = 3;       // 3 or 4 nodes
  std::array<long long, 4> nodes{};  // node IDs (the 4th is 0 for a triangle)
  std::array<int, 4> node_index{};   // ... as indices into Deck::nodes (-1 for a triangle's 4th)
  int file = 0, line = 0, lines = 1;
  FieldStyle style = FieldStyle::Fixed;
  std::string type;  // Abaqus element type (S4R, R3D3, ...); empty for the other formats
};

struct DeckPart {
  long long id = 0;
  std::string name;  // LS-DYNA *PART title, Abaqus ELSET name; empty when the deck has none
};

struct DeckSet {
  bool of_nodes = true;   // node set, or shell/element set
  // Nastran SET1 does not say what it holds: it is a grid set when its IDs are all grid IDs and not all
  // element IDs, an element set the other way round. IDs a THRU range names that the deck does not define
  // are left out, as Nastran does; when neither kind holds every ID, the one kind that holds every ID
  // given alone and some ID of the ranges is taken. Otherwise (IDs all both, grids and elements mixed, or
  // IDs the deck does not define) the kind is not known: members are then the IDs given alone and the
  // ranges' grids and elements, and of_nodes is meaningless -- unless a SPLINE1/2/4/5 names it as its SETG
  // (a set of grids) and it reads as grids. A SET3 says: GRID or ELEM.
  bool kind_known = true;
  std::string name;       // Abaqus set name or LS-DYNA title ("" when none)
  long long id = 0;       // LS-DYNA SID, Nastran SID (0 for Abaqus)
  std::string des;        // Nastran SET3's DES (GRID or ELEM); "" for SET1 and the other formats
  std::vector<long long> members;  // IDs, in the deck's order, ranges (GENERATE, THRU) expanded
  std::vector<std::string> named_members;  // Abaqus members that are other sets' names (kept as they are)
  int file = 0;
  int keyword_line = 0;                  // the *SET_.../*NSET/*ELSET line, Nastran: the card's first line
  int data_begin = 0, data_end = 0;      // lines holding the members (comments between included; Nastran:
                                         // the whole card, its first line too)
  bool generate = false;
  FieldStyle style = FieldStyle::Fixed;
};

// Records by ID: a table over the IDs' range when they are dense enough (the usual deck: O(1) and no
// hashing), else sorted (ID, record) pairs.
class IdIndex {
 public:
  // Indexes ids (record i has ids[i]). Returns {i, j}: the first record i (in order) whose ID the record
  // j < i already has, or {-1, -1} when the IDs are unique (the index is complete only then).
  std::pair<int, int> build(const std::vector<long long>& ids);
  int find(long long id) const;  // the record with this ID, or -1
  size_t size() const { return count_; }

 private:
  size_t count_ = 0;
  long long first_ = 0;                          // dense: table_[k] is the record of ID first_ + k, or -1
  std::vector<int> table_;
  std::vector<std::pair<long long, int>> sorted_;  // sparse
};

struct Deck {
  DeckFormat format = DeckFormat::LsDyna;
  std::vector<DeckFile> files;  // files[0] is the main file, then includes in the order met
  std::vector<DeckNode> nodes;
  std::vector<DeckShell> shells;
  std::vector<DeckPart> parts;
  std::vector<DeckSet> sets;
  long long max_node_id = 0;     // largest node ID in the deck
  long long max_element_id = 0;  // largest element ID of any element type the reader recognises
  IdIndex node_by_id, shell_by_id;  // made by parse_deck (IDs checked unique there)
};

// Reads `text` of a main file; includes are loaded through `load` (path relative to the including
// file's folder -> its text; return false if it cannot be read: then the deck is refused naming it).
using DeckLoader = std::function<bool(const std::string& path, std::string& text)>;
Deck parse_deck(const std::string& path, std::string text, DeckFormat format, const DeckLoader& load);
// Reads a file from disk (includes too), format by extension.
Deck read_deck(const std::string& path);

struct DeckEdits {
  std::vector<long long> removed_nodes, removed_shells;  // IDs whose records are dropped
  std::vector<DeckNode> new_nodes;                       // id and xyz used
  std::vector<DeckShell> new_shells;                     // id, part, count and nodes used
  std::vector<std::pair<int, std::vector<long long>>> set_members;  // set index -> its new member IDs
};

// The deck's files (in Deck::files order) with the edits applied: removed records' lines dropped, new
// nodes after the last node record, new shells after the last shell record (Abaqus: in new *ELEMENT
// blocks, one per part and type), rewritten sets in place; all other bytes unchanged. Throws
// invalid_input for an edit naming an unknown ID or set, a new ID already in use, or a new shell
// whose part the deck does not know in Abaqus.
std::vector<std::string> write_deck(const Deck& deck, const DeckEdits& edits);

}  // namespace meshround
