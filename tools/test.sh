#!/usr/bin/env bash
# The whole test suite: C++ unit tests (GoogleTest via ctest), then the Python tests (engine through
# Python, FreeCAD headless, the CLI) and the GUI tests (real FreeCAD under Xvfb), all with pytest; then
# half a minute of fuzzing on each of four targets (tools/fuzz.sh 30; longer runs: tools/fuzz.sh SECONDS).
# Exits non-zero on any failure.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$ROOT/tools/setup.sh"
cd "$ROOT"
ctest --test-dir build --output-on-failure -j2
# Two workers, each test file on one of them (a file's fixtures -- meshes, OCCT references, the GUI session
# -- are made once).
/usr/bin/python3 -m pytest -q -p no:cacheprovider -n 2 --dist loadfile tests
# A bounded fuzzing pass (tools/fuzz.sh), clang-14 + ASan + UBSan: 30 s on each target, each starting from its corpus (the seeds and the past findings). The array
# boundary's and the deck readers' targets must come back clean; the engine's two (round_edges, and change_radius on
# its results) still find the open faults listed in tests/fuzz/regressions/README.md, so their passes print what they
# find without failing the suite.
# (Two targets to a call: their builds share the two cores.)
"$ROOT/tools/fuzz.sh" 30 fuzz_arrays fuzz_decks
"$ROOT/tools/fuzz.sh" 30 fuzz_round fuzz_reround ||
  echo "fuzz_round, fuzz_reround: the findings above are kept in fuzz-out/<target>/artifacts (open faults)"
