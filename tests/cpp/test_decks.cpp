// Solver decks: each format's field layouts read to the values written, a byte-identical round trip
// without edits, edits that leave every other line as it was, and malformed lines refused with
// file:line and the reason.
#include <gtest/gtest.h>

#include <cstdio>
#include <map>

#include "deck_text.h"  // (private: the writers' field layout)
#include "meshround/deck.h"

using namespace meshround;

namespace {

// Right-aligned field of width w.
std::string f(int w, const std::string& s) { return std::string(std::max(0, w - int(s.size())), ' ') + s; }
std::string f(int w, long long x) { return f(w, std::to_string(x)); }

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  size_t a = 0;
  while (a < text.size()) {
    size_t b = text.find('\n', a);
    b = b == std::string::npos ? text.size() : b + 1;
    out.push_back(text.substr(a, b - a));
    a = b;
  }
  return out;
}

// How many of `before`'s lines are in `after`, in order (matched greedily).
int kept_in_order(const std::vector<std::string>& before, const std::vector<std::string>& after) {
  size_t j = 0;
  int kept = 0;
  for (const std::string& l : before) {
    size_t k = j;
    while (k < after.size() && after[k] != l) ++k;
    if (k < after.size()) ++kept, j = k + 1;
  }
  return kept;
}

Deck parse(const std::string& text, DeckFormat format, std::map<std::string, std::string> includes = {},
           const std::string& path = "dir/main") {
  return parse_deck(path, text, format, [includes](const std::string& p, std::string& t) {
    auto it = includes.find(p);
    if (it == includes.end()) return false;
    t = it->second;
    return true;
  });
}

std::string refusal(const std::string& text, DeckFormat format, std::map<std::string, std::string> includes = {}) {
  try {
    parse(text, format, includes);
  } catch (const RoundingError& e) {
    EXPECT_EQ(e.code, ErrorCode::InvalidInput);
    return e.what();
  }
  return "";
}

void expect_unchanged(const Deck& d) {
  const auto out = write_deck(d, DeckEdits());
  ASSERT_EQ(out.size(), d.files.size());
  for (size_t i = 0; i < out.size(); ++i) EXPECT_EQ(out[i], d.files[i].text) << d.files[i].path;
}

// Two quads (1: 1-2-5-4, 2: 2-3-6-5) and a triangle (3: 4-5-7) on a 3 x 2 grid of nodes plus one apex.
const double kX[7] = {0, 1, 2, 0, 1, 2, 0.5};
const double kY[7] = {0, 0, 0, 1, 1, 1, 2};
const long long kQuad[2][4] = {{1, 2, 5, 4}, {2, 3, 6, 5}};

std::string lsdyna_standard() {
  std::string t = "*KEYWORD\n$ a comment\n*TITLE\ndie\n*PART\ndie surface\n" + f(10, 7) + f(10, 1) + f(10, 1) + "\n*NODE\n";
  for (int i = 0; i < 7; ++i) {
    char buf[80];
    std::snprintf(buf, sizeof buf, "%8d%16.6f%16.6f%16.6f%8d%8d\n", i + 1, kX[i], kY[i], 0.0, 0, 0);
    t += buf;
  }
  t += "*ELEMENT_SHELL\n";
  for (int e = 0; e < 2; ++e) t += f(8, e + 1) + f(8, 7) + f(8, kQuad[e][0]) + f(8, kQuad[e][1]) + f(8, kQuad[e][2]) + f(8, kQuad[e][3]) + "\n";
  t += f(8, 3) + f(8, 7) + f(8, 4) + f(8, 5) + f(8, 7) + f(8, 7) + "\n";
  t += "*SET_SHELL_LIST_TITLE\nshoulder\n" + f(10, 11) + "\n" + f(10, 1) + f(10, 3) + "\n";
  t += "*SET_NODE_LIST_GENERATE\n" + f(10, 12) + "\n" + f(10, 1) + f(10, 3) + "\n";
  t += "*MAT_RIGID\n         1   7.8E-09  210000.0       0.3\n*END\n";
  return t;
}

TEST(DeckLsDyna, StandardFieldsReadAndRoundTrip) {
  const Deck d = parse(lsdyna_standard(), DeckFormat::LsDyna);
  ASSERT_EQ(d.nodes.size(), 7u);
  ASSERT_EQ(d.shells.size(), 3u);
  EXPECT_EQ(d.nodes[4].id, 5);
  EXPECT_DOUBLE_EQ(d.nodes[4].xyz.x(), 1.0);
  EXPECT_DOUBLE_EQ(d.nodes[6].xyz.y(), 2.0);
  EXPECT_EQ(d.shells[1].count, 4);
  EXPECT_EQ(d.shells[1].nodes[3], 5);
  EXPECT_EQ(d.shells[2].count, 3);  // n3 = n4: a triangle
  EXPECT_EQ(d.shells[2].part, 7);
  EXPECT_EQ(d.shells[2].node_index[2], 6);
  ASSERT_EQ(d.parts.size(), 1u);
  EXPECT_EQ(d.parts[0].name, "die surface");
  ASSERT_EQ(d.sets.size(), 2u);
  EXPECT_EQ(d.sets[0].name, "shoulder");
  EXPECT_EQ(d.sets[0].id, 11);
  EXPECT_EQ(d.sets[0].members, (std::vector<long long>{1, 3}));
  EXPECT_EQ(d.sets[1].members, (std::vector<long long>{1, 2, 3}));  // GENERATE 1..3
  EXPECT_EQ(d.max_node_id, 7);
  expect_unchanged(d);
}

// *PART options carry cards after the part card (_INERTIA: three more), and a part's title may be a blank
// line (LS-PrePost writes 80 spaces): it is still the title, and the next card the part's.
TEST(DeckLsDyna, PartWithBlankTitleAndInertiaCards) {
  std::string t = lsdyna_standard();
  const std::string inertia = "*PART_INERTIA\n$# title\n" + std::string(80, ' ') + "\n$#     pid     secid       mid\n" +
                              f(10, 9) + f(10, 2) + f(10, 2) + "\n" + f(10, 0) + f(10, 0) + f(10, 1) + "\n" +
                              "  0.0013833.3715e-041.1187e-079.3520e-04-1.491e-076.9611e-04\n" + f(10, 0) + f(10, 0) + "\n";
  t.insert(t.find("*NODE"), inertia);
  const Deck d = parse(t, DeckFormat::LsDyna);
  ASSERT_EQ(d.parts.size(), 2u);
  EXPECT_EQ(d.parts[1].id, 9);
  EXPECT_EQ(d.parts[1].name, "");
  EXPECT_EQ(d.shells.size(), 3u);
  expect_unchanged(d);
}

// Set members too wide for the fields are written free-format; a line holding one of them alone keeps a
// comma (without one it would be read in fixed fields, the ID cut at 10 characters).
TEST(DeckLsDyna, WideSetMembersWrittenFreeFormatReadBackWhole) {
  const std::vector<long long> ids{1, 2, 3, 4, 5, 6, 7, 8, 12345678901LL};
  const std::string text = decktext::lsdyna_members(ids, FieldStyle::Fixed, "\n");
  EXPECT_EQ(text, "1,2,3,4,5,6,7,8\n12345678901,\n");
  std::string t = lsdyna_standard();
  t.insert(t.find("*MAT_RIGID"), "*SET_NODE_LIST\n" + f(10, 13) + "\n" + text);
  const Deck d = parse(t, DeckFormat::LsDyna);
  ASSERT_EQ(d.sets.size(), 3u);
  EXPECT_EQ(d.sets[2].members, ids);
}

TEST(DeckLsDyna, LongI10AndFreeFormatLines) {
  // *NODE + (20 columns), *ELEMENT_SHELL % (10 columns), comma lines mixed in, CRLF line ends.
  std::string t = "*KEYWORD\r\n*NODE +\r\n";
  for (int i = 0; i < 6; ++i) t += f(20, 100000001 + i) + f(20, std::to_string(kX[i]) + "e0") + f(20, std::to_string(kY[i])) + f(20, "0.") + "\r\n";
  t += "101000007,0.5,2.0,0.0\r\n*ELEMENT_SHELL %\r\n";
  for (int e = 0; e < 2; ++e) {
    t += f(10, 1000000001 + e) + f(10, 2);
    for (int k = 0; k < 4; ++k) t += f(10, 100000000 + kQuad[e][k]);
    t += "\r\n";
  }
  t += "1000000003,2,100000004,100000005,101000007\r\n";
  const Deck d = parse(t, DeckFormat::LsDyna);
  ASSERT_EQ(d.nodes.size(), 7u);
  EXPECT_EQ(d.nodes[5].id, 100000006);
  EXPECT_DOUBLE_EQ(d.nodes[5].xyz.x(), 2.0);
  EXPECT_EQ(d.nodes[6].style, FieldStyle::Free);
  ASSERT_EQ(d.shells.size(), 3u);
  EXPECT_EQ(d.shells[1].nodes[0], 100000002);
  EXPECT_EQ(d.shells[2].count, 3);  // free format, 3 nodes given
  EXPECT_EQ(d.files[0].eol, "\r\n");
  expect_unchanged(d);
  // *KEYWORD LONG=Y makes every keyword long; a '-' suffix takes one back to standard.
  std::string g = "*KEYWORD LONG=Y\n*NODE\n" + f(20, 9) + f(20, "1.5") + f(20, "2.5") + f(20, "3.5") + "\n*NODE -\n" + f(8, 10) + f(16, "4.0") + f(16, "5.0") + f(16, "6.0") + "\n";
  const Deck l = parse(g, DeckFormat::LsDyna);
  ASSERT_EQ(l.nodes.size(), 2u);
  EXPECT_DOUBLE_EQ(l.nodes[0].xyz.z(), 3.5);
  EXPECT_EQ(l.nodes[1].id, 10);
  EXPECT_DOUBLE_EQ(l.nodes[1].xyz.z(), 6.0);
}

TEST(DeckLsDyna, IncludeFollowedAndMissingOneNamed) {
  const std::string main = "*KEYWORD\n*INCLUDE\nmesh.k\n*END\n";
  const Deck d = parse(main, DeckFormat::LsDyna, {{"dir/mesh.k", lsdyna_standard()}});
  ASSERT_EQ(d.files.size(), 2u);
  EXPECT_EQ(d.nodes.size(), 7u);
  EXPECT_EQ(d.shells[0].file, 1);
  expect_unchanged(d);
  EXPECT_NE(refusal(main, DeckFormat::LsDyna).find("dir/main:3: cannot read the included file 'dir/mesh.k'"), std::string::npos);
  EXPECT_NE(refusal("*INCLUDE_TRANSFORM\nx.k\n", DeckFormat::LsDyna).find("*INCLUDE_TRANSFORM is not followed"), std::string::npos);
  EXPECT_NE(refusal("*INCLUDE\nmain\n", DeckFormat::LsDyna, {{"dir/main", "*INCLUDE\nmain\n"}}).find("nested"), std::string::npos);
}

TEST(DeckLsDyna, MalformedLinesRefusedWithFileLineAndReason) {
  const auto base = lines(lsdyna_standard());  // line 9: node 1, line 10: node 2, line 19: element 3
  auto bad = [&](int line, const std::string& text) {
    auto l = base;
    l[line - 1] = text + "\n";
    std::string s;
    for (const auto& x : l) s += x;
    return refusal(s, DeckFormat::LsDyna);
  };
  EXPECT_NE(bad(9, f(8, 1) + f(16, "0.0x0") + f(16, "0.") + f(16, "0.")).find("dir/main:9: bad coordinate '0.0x0'"), std::string::npos);
  EXPECT_NE(bad(18, f(8, "2a") + f(8, 7) + f(8, 2) + f(8, 3) + f(8, 6) + f(8, 5)).find("dir/main:18: bad element ID '2a'"), std::string::npos);
  EXPECT_NE(bad(10, f(8, 1) + f(16, "1.") + f(16, "0.") + f(16, "0.")).find("node 1 is defined twice (also at dir/main:9)"), std::string::npos);
  EXPECT_NE(bad(19, f(8, 3) + f(8, 7) + f(8, 4) + f(8, 5) + f(8, 99) + f(8, 99)).find("dir/main:19: element 3 refers to node 99"), std::string::npos);
  EXPECT_NE(refusal("*ELEMENT_SHELL_COMPOSITE\n1\n", DeckFormat::LsDyna).find("COMPOSITE is not supported"), std::string::npos);
}

TEST(DeckLsDyna, EditsTouchOnlyTheirLines) {
  const Deck d = parse(lsdyna_standard(), DeckFormat::LsDyna);
  DeckEdits e;
  e.removed_shells = {3};
  e.removed_nodes = {7};
  DeckNode n;
  n.id = 8, n.xyz = Vec3(0.5, 1.5, 0.25);
  e.new_nodes = {n};
  DeckShell s;
  s.id = 4, s.part = 7, s.count = 3, s.nodes = {4, 5, 8, 0};
  e.new_shells = {s};
  e.set_members = {{0, {1, 4}}, {1, {1, 2, 3, 8}}};
  const std::string out = write_deck(d, e)[0];
  const auto before = lines(d.files[0].text), after = lines(out);
  // Removed: node 7 and element 3; added: one node, one element; sets: the GENERATE set lists 4 members.
  EXPECT_EQ(after.size(), before.size());
  const Deck r = parse(out, DeckFormat::LsDyna);
  ASSERT_EQ(r.nodes.size(), 7u);
  EXPECT_EQ(r.nodes.back().id, 8);
  EXPECT_NEAR(r.nodes.back().xyz.z(), 0.25, 1e-12);
  ASSERT_EQ(r.shells.size(), 3u);
  EXPECT_EQ(r.shells.back().id, 4);
  EXPECT_EQ(r.shells.back().nodes[2], 8);
  EXPECT_EQ(r.sets[0].members, (std::vector<long long>{1, 4}));
  EXPECT_EQ(r.sets[1].members, (std::vector<long long>{1, 2, 3, 8}));
  EXPECT_FALSE(r.sets[1].generate);
  // Every line of the input that names no edited record is in the output, in order.
  const int kept = kept_in_order(before, after);
  EXPECT_EQ(kept, int(before.size()) - 5);  // node 7, element 3, two set data lines, the GENERATE keyword line
  // A removed node an element keeps, and an ID in use, are refused.
  DeckEdits dangling;
  dangling.removed_nodes = {5};
  EXPECT_THROW(write_deck(d, dangling), RoundingError);
  DeckEdits reused;
  reused.new_nodes = {DeckNode{3, Vec3::Zero()}};
  EXPECT_THROW(write_deck(d, reused), RoundingError);
}

std::string nastran_deck() {
  std::string t = "SOL 101\nCEND\nBEGIN BULK\n$ die\nPSHELL  7       1       1.0\n";
  t += "GRID    1               0.      0.      0.\n";                    // small field
  t += "GRID*   2                               1.0             0.0\n*       0.0\n";  // large field
  t += "GRID,3,,2.,0.,0.\n";                                                // free field
  t += "GRID    4               0.      1.      -1.-1\n";                 // implied exponent: -0.1
  t += "GRID    5               1.      1.      0.\nGRID    6               2.      1.      0.\n";
  t += "GRID    7               .5      2.      0.\n";
  t += "CQUAD4  1       7       1       2       5       4       0.      +C1\n+C1             0.1\n";
  t += "CQUAD4* 2               7               2               3\n*       6               5\n";
  t += "CTRIA3,3,7,4,5,7\nCBAR    99      1       1       2\nENDDATA\n";
  return t;
}

TEST(DeckNastran, SmallLargeFreeContinuationsRoundTrip) {
  const Deck d = parse(nastran_deck(), DeckFormat::Nastran);
  ASSERT_EQ(d.nodes.size(), 7u);
  EXPECT_DOUBLE_EQ(d.nodes[1].xyz.x(), 1.0);
  EXPECT_EQ(d.nodes[1].lines, 2);
  EXPECT_EQ(d.nodes[1].style, FieldStyle::Long);
  EXPECT_DOUBLE_EQ(d.nodes[2].xyz.x(), 2.0);
  EXPECT_DOUBLE_EQ(d.nodes[3].xyz.z(), -0.1);
  EXPECT_DOUBLE_EQ(d.nodes[6].xyz.x(), 0.5);
  ASSERT_EQ(d.shells.size(), 3u);
  EXPECT_EQ(d.shells[0].lines, 2);
  EXPECT_EQ(d.shells[1].nodes[3], 5);
  EXPECT_EQ(d.shells[2].count, 3);
  EXPECT_EQ(d.max_element_id, 99);
  ASSERT_EQ(d.parts.size(), 1u);
  EXPECT_EQ(d.parts[0].id, 7);
  expect_unchanged(d);
}

TEST(DeckNastran, EditsAndErrors) {
  const Deck d = parse(nastran_deck(), DeckFormat::Nastran);
  DeckEdits e;
  e.removed_shells = {1};
  e.new_nodes = {DeckNode{100000123, Vec3(0.5, 0.5, -1e-3)}};
  DeckShell s;
  s.id = 123456789, s.part = 7, s.count = 4, s.nodes = {1, 2, 5, 100000123};
  e.new_shells = {s};
  const std::string out = write_deck(d, e)[0];
  const Deck r = parse(out, DeckFormat::Nastran);
  ASSERT_EQ(r.nodes.size(), 8u);
  EXPECT_NEAR(r.nodes.back().xyz.z(), -1e-3, 1e-12);
  ASSERT_EQ(r.shells.size(), 3u);
  EXPECT_EQ(r.shells.back().id, 123456789);  // 9 digits: written in large field
  EXPECT_EQ(r.shells.back().nodes[3], 100000123);
  EXPECT_EQ(out.find("+C1"), std::string::npos);  // the removed element's continuation went with it
  EXPECT_NE(refusal("BEGIN BULK\nGRID    1       5       0.      0.      0.\n", DeckFormat::Nastran).find("dir/main:2: GRID 1 is given in coordinate system 5"), std::string::npos);
  EXPECT_NE(refusal("GRID    1               0.      0.      abc\n", DeckFormat::Nastran).find("dir/main:1: bad GRID coordinate 'abc'"), std::string::npos);
  EXPECT_NE(refusal("+C1     1\n", DeckFormat::Nastran).find("continuation line without a card"), std::string::npos);
  EXPECT_NE(refusal("INCLUDE 'grids.bdf'\n", DeckFormat::Nastran).find("cannot read the included file 'dir/grids.bdf'"), std::string::npos);
  // Tabs move to the next 8-column field; a quoted INCLUDE name may continue on the next line.
  const Deck tabs = parse("GRID\t7\t\t0.5\t1.\t-2.\n", DeckFormat::Nastran);
  ASSERT_EQ(tabs.nodes.size(), 1u);
  EXPECT_DOUBLE_EQ(tabs.nodes[0].xyz.x(), 0.5);
  EXPECT_DOUBLE_EQ(tabs.nodes[0].xyz.z(), -2.0);
  EXPECT_NE(refusal("INCLUDE 'sub/\n  g.bdf'\n", DeckFormat::Nastran).find("dir/main:1: cannot read the included file 'dir/sub/g.bdf'"), std::string::npos);
  const Deck inc = parse("BEGIN BULK\nINCLUDE 'g.bdf'\nCTRIA3  1       2       1       2       3\n", DeckFormat::Nastran,
                         {{"dir/g.bdf", "GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nGRID,3,,0.,1.,0.\n"}});
  EXPECT_EQ(inc.nodes.size(), 3u);
  EXPECT_EQ(inc.shells.size(), 1u);
  expect_unchanged(inc);
}

// nastran_deck()'s grids 1-7 and elements 1-3 (shells) and 99 (a CBAR), with sets: IDs 1-3 are both.
std::string nastran_sets_deck() {
  std::string t = nastran_deck();
  t.erase(t.find("ENDDATA"));
  t += "SET1    21      1       2       THRU    5\n";       // grids (2-5: not all elements): 1-5
  t += "SET1,22,1,3,99\n";                                   // elements (99 is no grid): 1, 3, 99
  t += "SET1    23      1       2\n";                        // both: kind not known
  t += "SET1*   24              6               7\n*       1\n";  // large field, continued: grids
  t += "$ a comment inside a card\n+       3\n";             // ... and on, past a comment
  t += "SET3    25      ELEM    1       THRU    3\n";        // SET3: as it says
  t += "SET1    26      5       thru    8\n";                // 8 is nothing: grids 5-7
  t += "SET1    27      SKIN    1\nRBE2    500     1       123456  2\n";  // SKIN: not read
  t += "SET1    28      1       2       3\n";                // both: kind not known ...
  t += "SPLINE1 40      1000    1001    1010    28\nENDDATA\n";  // ... but a spline's grids
  return t;
}

TEST(DeckNastran, SetsReadAsGridsOrElementsByTheirIds) {
  const Deck d = parse(nastran_sets_deck(), DeckFormat::Nastran);
  ASSERT_EQ(d.sets.size(), 7u);
  const std::vector<long long> members[7] = {{1, 2, 3, 4, 5}, {1, 3, 99}, {1, 2}, {6, 7, 1, 3}, {1, 2, 3}, {5, 6, 7}, {1, 2, 3}};
  const bool nodes[7] = {true, false, false, true, false, true, true}, known[7] = {true, true, false, true, true, true, true};
  for (int i = 0; i < 7; ++i) {
    EXPECT_EQ(d.sets[i].id, i < 6 ? 21 + i : 28);
    EXPECT_EQ(d.sets[i].members, members[i]) << i;
    EXPECT_EQ(d.sets[i].kind_known, known[i]) << i;
    if (known[i]) EXPECT_EQ(d.sets[i].of_nodes, nodes[i]) << i;
  }
  EXPECT_EQ(d.sets[1].style, FieldStyle::Free);
  EXPECT_EQ(d.sets[3].style, FieldStyle::Long);
  EXPECT_EQ(d.sets[3].data_end - d.sets[3].data_begin, 4);  // two lines, the comment and the last
  EXPECT_EQ(d.sets[4].des, "ELEM");
  EXPECT_EQ(d.max_element_id, 500);  // a rigid element's ID counts
  expect_unchanged(d);
}

TEST(DeckNastran, ChangedSetsRewrittenInTheirOwnFieldsTheRestKept) {
  const Deck d = parse(nastran_sets_deck(), DeckFormat::Nastran);
  DeckEdits e;
  e.set_members = {{0, {7, 1, 2, 3, 4, 5, 6}}, {1, {3, 99, 123456789}}, {2, {1, 2, 3}}, {3, {6, 1, 3, 7, 2, 4, 5}}, {4, {1, 3}}, {5, {5, 6, 123456789}}};
  const std::string out = write_deck(d, e)[0];
  EXPECT_NE(out.find("\nSET1    21      7       1       THRU    6\n"), std::string::npos);  // a run as a range
  EXPECT_NE(out.find("\nSET1    23      1       2       3\n"), std::string::npos);  // kind unknown: no range
  EXPECT_NE(out.find("\nSET1,22,3,99,123456789\n"), std::string::npos);
  EXPECT_NE(out.find("\nSET1*   24              6               1               3\n*       7               2               4               5\n"), std::string::npos);
  EXPECT_NE(out.find("\nSET1*   26              5               6               123456789\n"), std::string::npos);  // too wide for 8
  EXPECT_NE(out.find("\nSET3    25      ELEM    1       3\n"), std::string::npos);
  // Every other line as it was, in order: the six cards' 8 lines and the comment inside one went.
  const auto before = lines(d.files[0].text), after = lines(out);
  const int kept = kept_in_order(before, after);
  EXPECT_EQ(kept, int(before.size()) - 9);
  const Deck r = parse(out, DeckFormat::Nastran);
  ASSERT_EQ(r.sets.size(), 7u);
  EXPECT_EQ(r.sets[0].members, (std::vector<long long>{7, 1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(r.sets[3].members, (std::vector<long long>{6, 1, 3, 7, 2, 4, 5}));
  EXPECT_EQ(r.sets[4].members, (std::vector<long long>{1, 3}));
  EXPECT_THROW(write_deck(d, DeckEdits{{}, {}, {}, {}, {{0, {}}}}), RoundingError);    // no ID left
  EXPECT_THROW(write_deck(d, DeckEdits{{}, {}, {}, {}, {{0, {1, -2}}}}), RoundingError);
}

TEST(DeckNastran, MalformedSetsRefusedWithFileLineAndReason) {
  const std::pair<const char*, const char*> cases[] = {
      {"SET1    5       1       THRU\n", "dir/main:1: SET1 5: THRU without an ID after it"},
      {"SET1    5       THRU    3\n", "dir/main:1: SET1 5: THRU without an ID before it"},
      {"SET1    5       1       THRU    4       THRU    9\n", "dir/main:1: SET1 5: THRU without an ID before it"},
      {"SET1    5       9       THRU    3\n", "dir/main:1: SET1 5: bad THRU range 9 THRU 3"},
      {"GRID,1,,0.,0.,0.\nSET1    5       1\n        x\n", "dir/main:3: bad SET1 ID 'x'"},
      {"SET1    0       1\n", "dir/main:1: SET1 SID must be positive, got 0"},
      {"SET1,a,1\n", "dir/main:1: bad SET1 SID 'a'"},
      {"SET1    5\n", "dir/main:1: SET1 5 lists no ID"},
      {"SET3    5               1\n", "dir/main:1: SET3 5 has no DES"},
      {"SET1,5,1,2,3,4,5,6,7,8,,9\n", "dir/main:1: SET1: more than 10 fields on a free-field line"},
  };
  for (const auto& [text, why] : cases) EXPECT_NE(refusal(text, DeckFormat::Nastran).find(why), std::string::npos) << text;
  // Not read, kept: OptiStruct's EXCEPT, ZAERO's negative IDs, SET3 of properties.
  EXPECT_TRUE(parse("SET1    5       1       THRU    9       EXCEPT  4\nSET1    7       1       -4\nSET3    6       PROP    1\n",
                    DeckFormat::Nastran).sets.empty());
}

std::string abaqus_deck() {
  std::string t = "*HEADING\ndie\n** comment\n*NODE, NSET=ALL\n";
  for (int i = 0; i < 7; ++i) t += std::to_string(i + 1) + ", " + std::to_string(kX[i]) + ", " + std::to_string(kY[i]) + ", 0.\n";
  t += "*ELEMENT, TYPE=S4R, ELSET=DIE\n1, 1, 2, 5, 4\n2, 2, 3,\n 6, 5\n*ELEMENT, TYPE=S3R, ELSET=DIE\n3, 4, 5, 7\n";
  t += "*ELEMENT, TYPE=C3D8, ELSET=BLOCK\n50, 1, 2, 3, 4, 5, 6, 7, 1\n";
  t += "*NSET, NSET=EDGE, GENERATE\n1, 3, 1\n*ELSET, ELSET=BAND\n1, 3, DIE\n*MATERIAL, NAME=STEEL\n*ELASTIC\n210000., 0.3\n";
  return t;
}

TEST(DeckAbaqus, ElementsSetsIncludesRoundTrip) {
  const Deck d = parse(abaqus_deck(), DeckFormat::Abaqus);
  ASSERT_EQ(d.nodes.size(), 7u);
  ASSERT_EQ(d.shells.size(), 3u);
  EXPECT_EQ(d.shells[1].lines, 2);  // continued with a trailing comma
  EXPECT_EQ(d.shells[1].nodes[3], 5);
  EXPECT_EQ(d.shells[2].type, "S3R");
  EXPECT_EQ(d.shells[0].part, d.shells[2].part);
  EXPECT_EQ(d.max_element_id, 50);
  ASSERT_EQ(d.sets.size(), 2u);
  EXPECT_EQ(d.sets[0].members, (std::vector<long long>{1, 2, 3}));
  EXPECT_EQ(d.sets[1].members, (std::vector<long long>{1, 3}));
  EXPECT_EQ(d.sets[1].named_members, (std::vector<std::string>{"DIE"}));
  expect_unchanged(d);
  // *INCLUDE: the included data lines continue the keyword before it.
  const Deck inc = parse("*NODE\n*INCLUDE, INPUT=nodes.inp\n*ELEMENT, TYPE=S3\n1, 1, 2, 3\n", DeckFormat::Abaqus,
                         {{"dir/nodes.inp", "1, 0., 0., 0.\n2, 1., 0., 0.\n3, 0., 1., 0.\n"}});
  EXPECT_EQ(inc.nodes.size(), 3u);
  EXPECT_EQ(inc.nodes[2].file, 1);
  expect_unchanged(inc);
}

TEST(DeckAbaqus, EditsAndErrors) {
  const Deck d = parse(abaqus_deck(), DeckFormat::Abaqus);
  DeckEdits e;
  e.removed_shells = {1};
  e.new_nodes = {DeckNode{8, Vec3(0.5, 0.5, 0.1)}};
  DeckShell tri;
  tri.id = 51, tri.part = d.shells[0].part, tri.count = 3, tri.nodes = {1, 2, 8, 0};
  DeckShell quad = tri;
  quad.id = 52, quad.count = 4, quad.nodes = {1, 8, 5, 4};
  e.new_shells = {tri, quad};
  e.set_members = {{0, {1, 2, 3, 8}}, {1, {3, 51, 52}}};
  const std::string out = write_deck(d, e)[0];
  const Deck r = parse(out, DeckFormat::Abaqus);
  ASSERT_EQ(r.shells.size(), 4u);
  EXPECT_EQ(r.shells[2].type, "S3R");  // a new triangle in DIE takes DIE's triangle type
  EXPECT_EQ(r.shells[3].type, "S4R");
  EXPECT_EQ(r.shells[3].part, r.shells[0].part);
  EXPECT_EQ(r.sets[0].members, (std::vector<long long>{1, 2, 3, 8}));
  EXPECT_FALSE(r.sets[0].generate);
  EXPECT_EQ(r.sets[1].members, (std::vector<long long>{3, 51, 52}));
  EXPECT_EQ(r.sets[1].named_members, (std::vector<std::string>{"DIE"}));
  EXPECT_NE(out.find("*NSET, NSET=EDGE\n"), std::string::npos);
  EXPECT_NE(refusal("*ELEMENT, TYPE=S4R\n1, 1, 2, 3\n", DeckFormat::Abaqus).find("dir/main:2: element 1 of TYPE=S4R needs 4 nodes, has 3"), std::string::npos);
  EXPECT_NE(refusal("*NODE\n1, 0., zero, 0.\n", DeckFormat::Abaqus).find("dir/main:2: bad coordinate 'zero'"), std::string::npos);
  EXPECT_NE(refusal("*NSET, NSET=A, GENERATE\n5, 1\n", DeckFormat::Abaqus).find("bad GENERATE range"), std::string::npos);
  EXPECT_NE(refusal("*ELEMENT\n1, 1, 2, 3\n", DeckFormat::Abaqus).find("without TYPE"), std::string::npos);
}

TEST(DeckFormats, ChosenByExtension) {
  EXPECT_EQ(deck_format_for("a/die.K"), DeckFormat::LsDyna);
  EXPECT_EQ(deck_format_for("die.dyn"), DeckFormat::LsDyna);
  EXPECT_EQ(deck_format_for("die.nas"), DeckFormat::Nastran);
  EXPECT_EQ(deck_format_for("die.dat"), DeckFormat::Nastran);
  EXPECT_EQ(deck_format_for("die.inp"), DeckFormat::Abaqus);
  EXPECT_THROW(deck_format_for("die.stl"), RoundingError);
  EXPECT_THROW(deck_format_for("dir.k/die"), RoundingError);
}

}  // namespace
