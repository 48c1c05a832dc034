#!/usr/bin/env bash
# ASan + UBSan build (gcc, -DMESHROUND_SANITIZE=ON) of the engine, the C++ tests and the Python module in
# build-asan/, then: ctest under it, and pytest on a few Python test files with the sanitized module
# (a copy of the workbench in build-asan/Mod, libasan preloaded into /usr/bin/python3, leaks off: the
# interpreter and FreeCAD keep memory to the end). Exits non-zero when either reports a failure.
#   tools/sanitize.sh [PYTEST FILES...]    default: tests/python/test_api.py tests/python/test_bad_mesh.py
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="$ROOT/build-asan"
MOD="$BUILD/Mod/MeshRound"
JOBS="${MESHROUND_SANITIZE_BUILD_JOBS:-2}"
mkdir -p "$MOD"
# The workbench's Python files, without the module built in the source tree.
tar -C "$ROOT/Mod/MeshRound" --exclude='_meshround_core*.so' --exclude=__pycache__ -cf - . | tar -C "$MOD" -xf -
cp -r "$ROOT/resources" "$BUILD/"  # the CLI's demo script, found beside the workbench's copy
cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMESHROUND_SANITIZE=ON -DMESHROUND_BUILD_BENCH=OFF \
  -DMESHROUND_MODULE_DIR="$MOD/MeshRound" > "$BUILD.log" 2>&1 || { cat "$BUILD.log"; exit 1; }
cmake --build "$BUILD" -j"$JOBS" >> "$BUILD.log" 2>&1 || { tail -50 "$BUILD.log"; exit 1; }

status=0
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=0:abort_on_error=0}" UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
echo "== ctest (ASan + UBSan)"
ctest --test-dir "$BUILD" --output-on-failure -j1 || status=1
(($#)) || set -- "$ROOT/tests/python/test_api.py" "$ROOT/tests/python/test_bad_mesh.py"
# The tests' yardstick module (tests/python/_yardstick) is the normal build's (a sanitized one would not load
# without the preload): made by tools/setup.sh when it is not there yet.
compgen -G "$ROOT/tests/python/_yardstick*.so" > /dev/null || "$ROOT/tools/setup.sh" > /dev/null
echo "== pytest with the sanitized module: $*"
# Left out here, run in the normal suite only: tests that start freecadcmd or the demo (a child inherits the
# preloaded sanitizer runtime and needs minutes to start under it), tests of the command line run as a child
# `python3 -m MeshRound.cli` (it imports the workbench from the source tree, not this build's), and the
# cancel test's 0.5 s bound (the sanitized engine polls several times slower).
DESELECT="freecadcmd or demo_runs or file_open_and_import or reported_on_freecads_console or command_line_max_radius or sweep_of_a_deck_with_includes or cancel_from_another_thread"
LD_PRELOAD="$(gcc -print-file-name=libasan.so):$(gcc -print-file-name=libubsan.so)" MESHROUND_MOD_DIR="$MOD" \
  /usr/bin/python3 -m pytest -q -p no:cacheprovider -k "not ($DESELECT)" "$@" || status=1
exit $status
