// libFuzzer harness for the solver-deck readers (deck.h). Input: one format byte, then the main file's
// text; a NUL byte splits off the text every include resolves to. A failure must be a RoundingError
// (invalid_input); a deck that reads must write back byte-identical, and still read with its first shell
// element removed.
#include <cstdint>
#include <cstdio>
#include <string>

#include "meshround/deck.h"

namespace {
void finding(const char* what) {
  std::fprintf(stderr, "FINDING: %s\n", what);
  __builtin_trap();
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace meshround;
  if (size < 1) return 0;
  const DeckFormat format = data[0] % 3 == 0 ? DeckFormat::LsDyna : data[0] % 3 == 1 ? DeckFormat::Nastran : DeckFormat::Abaqus;
  const std::string all(reinterpret_cast<const char*>(data + 1), size - 1);
  const size_t nul = all.find('\0');
  const std::string main = all.substr(0, nul);
  const std::string include = nul == std::string::npos ? std::string() : all.substr(nul + 1);
  const DeckLoader load = [&](const std::string&, std::string& text) {
    if (nul == std::string::npos) return false;
    text = include;
    return true;
  };
  Deck deck;
  try {
    deck = parse_deck("main", main, format, load);
  } catch (const RoundingError& e) {
    if (e.code != ErrorCode::InvalidInput) finding("a refusal that is not invalid_input");
    return 0;
  }
  const auto same = write_deck(deck, DeckEdits());
  for (size_t i = 0; i < same.size(); ++i)
    if (same[i] != deck.files[i].text) finding("a deck written without edits differs from its input");
  if (deck.shells.empty() || deck.files.size() > 2) return 0;  // (every include reads the same text)
  DeckEdits edits;
  edits.removed_shells = {deck.shells[0].id};
  const auto cut = write_deck(deck, edits);
  try {
    const std::string cut_include = cut.size() > 1 ? cut[1] : include;
    const DeckLoader load_cut = [&](const std::string&, std::string& text) {
      if (nul == std::string::npos) return false;
      text = cut_include;
      return true;
    };
    const Deck again = parse_deck("main", cut[0], format, load_cut);
    if (again.shells.size() + 1 != deck.shells.size())
      finding("removing one shell did not leave one fewer");
  } catch (const RoundingError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    finding("a deck with one shell removed no longer reads");
  }
  return 0;
}
