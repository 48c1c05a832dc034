// The solver-deck readers' fuzz case (fuzz_decks.cpp), shared with the regression replay
// (tests/cpp/test_fuzz_regressions.cpp). Input: one format byte, then the main file's text; a NUL byte
// splits off the text every include resolves to. A refusal must be a RoundingError (invalid_input); a
// deck that reads must write back byte-identical, and still read with its first shell element removed.
// Returns "" or what broke.
#pragma once
#include <cstdint>
#include <string>

#include "meshround/deck.h"

namespace meshround::fuzz {

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
  if (deck.shells.empty() || deck.files.size() > 2) return "";  // (every include reads the same text)
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
