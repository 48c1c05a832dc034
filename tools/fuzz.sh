#!/usr/bin/env bash
# Builds the libFuzzer targets (clang-14, ASan + UBSan) into build-fuzz/ and runs each for SECONDS
# (default 60): fuzz_round (the engine on generated meshes), fuzz_reround (change_radius on their rounded
# results), fuzz_arrays (raw arrays at the boundary) and fuzz_decks (the solver-deck readers and writer). Prints executions, corpus size, coverage (cov / ft) and findings of each; exits non-zero
# when a target found a crash, a sanitizer report, an invariant break or a timeout (> 10 s per input).
#   tools/fuzz.sh [SECONDS] [TARGET...]     corpora and findings: fuzz-out/<target>/
# A finding is replayed with:  build-fuzz/tests/fuzz/<target> fuzz-out/<target>/artifacts/<file>
# (MESHROUND_FUZZ_VERBOSE=1 prints the decoded case) and minimised with -minimize_crash=1 -runs=2000.
# Long runs: MESHROUND_FUZZ_MAX_NEW_FACETS=20000 caps every fuzz_round case's work budget (a case that would
# make more is refused with work_limit before it is made), so that the slow tail does not set the rate.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
SECONDS_EACH="${1:-60}"
shift || true
TARGETS=("$@")
((${#TARGETS[@]})) || TARGETS=(fuzz_round fuzz_reround fuzz_arrays fuzz_decks)
BUILD="$ROOT/build-fuzz"
JOBS="${MESHROUND_FUZZ_BUILD_JOBS:-2}"

command -v clang++-14 >/dev/null || { echo "fuzz.sh: clang++-14 is missing (tools/setup.sh installs clang-14, libfuzzer-14-dev, libclang-rt-14-dev)"; exit 1; }
if [ ! -f "$BUILD/CMakeCache.txt" ]; then
  cmake -S "$ROOT" -B "$BUILD" -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMESHROUND_BUILD_FUZZ=ON \
    -DMESHROUND_BUILD_TESTS=OFF -DMESHROUND_BUILD_BENCH=OFF -DMESHROUND_MODULE_DIR="$BUILD/module" > "$BUILD.log" 2>&1 \
    || { cat "$BUILD.log"; exit 1; }
fi
cmake --build "$BUILD" -j"$JOBS" --target "${TARGETS[@]}" >> "$BUILD.log" 2>&1 || { tail -50 "$BUILD.log"; exit 1; }

status=0
for t in "${TARGETS[@]}"; do
  out="$ROOT/fuzz-out/$t"
  mkdir -p "$out/corpus" "$out/artifacts"
  if [ "$t" = fuzz_decks ]; then  # decks in the three formats (tests/fuzz/deck_seeds), and past findings
    cp -n "$ROOT"/tests/fuzz/deck_seeds/* "$ROOT"/tests/fuzz/regressions/decks/*/* "$out/corpus/" 2>/dev/null || true
  fi
  [ -n "$(ls -A "$out/corpus")" ] || python3 "$ROOT/tests/fuzz/make_corpus.py" "$out/corpus" 48
  # Past findings that are fixed stay in the corpus: they lead back to the places that broke (the open ones
  # are slow: a bounded pass would spend itself on them).
  # (fuzz_reround decodes the same bytes as fuzz_round: the engine's findings seed it too.)
  case "$t" in fuzz_round|fuzz_reround) cp -n "$ROOT"/tests/fuzz/regressions/round/fixed/* "$out/corpus/" 2>/dev/null || true ;; esac
  before=$(ls "$out/artifacts" | wc -l)
  log="$out/last.log"
  rc=0
  # fuzz_round: no leak pass. OCCT keeps caches across calls, so every input's mallocs and frees differ and
  # libFuzzer would run each input a second time looking for a leak (half the executions).
  extra=()
  case "$t" in fuzz_round|fuzz_reround) extra=(-detect_leaks=0) ;; esac
  "$BUILD/tests/fuzz/$t" -max_total_time="$SECONDS_EACH" -timeout=10 -rss_limit_mb=2048 -max_len=256 -print_final_stats=1 \
    "${extra[@]}" -artifact_prefix="$out/artifacts/" "$out/corpus" > "$log" 2>&1 || rc=$?
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -1 || true)
  persec=$(grep -o 'stat::average_exec_per_sec: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -1 || true)
  last=$(grep -E '^#[0-9]+.*cov: ' "$log" | tail -1 || true)
  cov=$(sed -n 's/.*cov: \([0-9]*\).*/\1/p' <<<"$last"); ft=$(sed -n 's/.*ft: \([0-9]*\).*/\1/p' <<<"$last")
  corp=$(ls "$out/corpus" | wc -l)
  new=$(( $(ls "$out/artifacts" | wc -l) - before ))
  echo "$t: ${SECONDS_EACH}s, ${execs:-?} executions (${persec:-?}/s), corpus $corp inputs, cov ${cov:-?}, ft ${ft:-?}, new findings $new (exit $rc)"
  if [ "$rc" -ne 0 ]; then
    status=1
    grep -E 'FINDING|ERROR: (AddressSanitizer|libFuzzer|UndefinedBehaviorSanitizer)|runtime error|Test unit written' "$log" | head -5 | sed 's/^/  /'
    echo "  full log: $log"
  fi
done
exit $status
