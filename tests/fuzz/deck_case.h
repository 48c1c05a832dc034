// The solver-deck readers' fuzz case (fuzz_decks.cpp), shared with the regression replay
// (tests/cpp/test_fuzz_regressions.cpp). Input: one format byte, then the main file's text; a NUL byte
// splits off the text every include resolves to. A refusal must be a RoundingError (invalid_input); a
// deck that reads must write back byte-identical, and still read with its first shell element removed;
// a Nastran set rewritten with its own members must read back the same.
// Returns "" or what broke.
#pragma once
#include <cstdint>
#include <string>

#include "meshround/deck.h"

namespace meshround::fuzz {

// A Nastran deck's first set of known kind, rewritten with its own members, reads back as the same set.
// (A set of unknown kind is never rewritten by a rounding: deck_edit.py refuses instead.)
inline std::string nastran_set_rewrite(const Deck& deck, const DeckLoader& load, std::string& include) {
  if (deck.format != DeckFormat::Nastran) return "";
  int index = 0;
  while (index < int(deck.sets.size()) && !(deck.sets[index].kind_known && !deck.sets[index].members.empty())) ++index;
  if (index == int(deck.sets.size())) return "";
  const DeckSet& s = deck.sets[index];
  DeckEdits edits;
  edits.set_members = {{index, s.members}};
  const auto out = write_deck(deck, edits);
  const std::string kept = include;
  if (out.size() > 1) include = out[1];
  std::string finding;
  try {
    const Deck again = parse_deck("main", out[0], deck.format, load);
    if (again.sets.size() != deck.sets.size() || again.sets[index].members != s.members || !again.sets[index].kind_known ||
        again.sets[index].of_nodes != s.of_nodes)
      finding = "a Nastran set rewritten with its own members reads back otherwise";
  } catch (const RoundingError& e) {
    finding = std::string("a Nastran deck with a set rewritten no longer reads: ") + e.what();
  }
  include = kept;
  return finding;
}

inline std::string deck_case(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return "";
  const DeckFormat format = data[0] % 3 == 0 ? DeckFormat::LsDyna : data[0] % 3 == 1 ? DeckFormat::Nastran : DeckFormat::Abaqus;
  const std::string all(reinterpret_cast<const char*>(data + 1), size - 1);
  const size_t nul = all.find('\0');
  const std::string main = all.substr(0, nul);
  std::string include = nul == std::string::npos ? std::string() : all.substr(nul + 1);
  const DeckLoader load = [&](const std::string&, std::string& text) {
    if (nul == std::string::npos) return false;
    text = include;
    return true;
  };
  Deck deck;
  try {
    deck = parse_deck("main", main, format, load);
  } catch (const RoundingError& e) {
    return e.code == ErrorCode::InvalidInput ? "" : "a refusal that is not invalid_input";
  }
  const auto same = write_deck(deck, DeckEdits());
  for (size_t i = 0; i < same.size(); ++i)
    if (same[i] != deck.files[i].text) return "a deck written without edits differs from its input";
  if (deck.files.size() > 2) return "";  // (every include reads the same text)
  const std::string set_finding = nastran_set_rewrite(deck, load, include);
  if (!set_finding.empty()) return set_finding;
  if (deck.shells.empty()) return "";
  DeckEdits edits;
  edits.removed_shells = {deck.shells[0].id};
  const auto cut = write_deck(deck, edits);
  if (cut.size() > 1) include = cut[1];
  try {
    const Deck again = parse_deck("main", cut[0], format, load);
    if (again.shells.size() + 1 != deck.shells.size()) return "removing one shell did not leave one fewer";
  } catch (const RoundingError& e) {
    return std::string("a deck with one shell removed no longer reads: ") + e.what();
  }
  return "";
}

}  // namespace meshround::fuzz
