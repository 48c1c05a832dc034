#!/usr/bin/env bash
# Installs what MeshRound needs from Debian 12's archive (only what is missing), builds it with CMake,
# and installs the workbench into FreeCAD's user Mod folder. Safe to run again: a second run only
# rebuilds what changed.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

PACKAGES=(
  cmake g++ make
  freecad freecad-python3                       # FreeCAD 0.20 and its Python (/usr/bin/python3)
  libocct-foundation-dev libocct-modeling-data-dev libocct-modeling-algorithms-dev
  libocct-data-exchange-dev libocct-ocaf-dev libocct-visualization-dev   # OCCT 7.6, as FreeCAD links
  libtbb-dev                                    # OCCT's CMake config links libtbb.so
  pybind11-dev libeigen3-dev
  libgtest-dev libbenchmark-dev
  python3-pytest python3-pytest-xdist python3-numpy python3-scipy   # xdist: the suite's files on two cores
  gmsh                                          # tests: meshes of the CAD solids from another mesher
  xvfb xauth                                    # the GUI tests run FreeCAD under Xvfb
  clang-14 libfuzzer-14-dev libclang-rt-14-dev  # tools/fuzz.sh: libFuzzer with ASan + UBSan
)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  echo "Installing: ${missing[*]}"
  $SUDO apt-get update -q
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

cmake -S "$ROOT" -B "$ROOT/build" -DCMAKE_BUILD_TYPE=Release > "$ROOT/build.log" 2>&1 || { cat "$ROOT/build.log"; exit 1; }
cmake --build "$ROOT/build" -j"$(nproc)" >> "$ROOT/build.log" 2>&1 || { tail -50 "$ROOT/build.log"; exit 1; }
cmake --install "$ROOT/build" >> "$ROOT/build.log" 2>&1 || { tail -20 "$ROOT/build.log"; exit 1; }
MOD_DIR="$HOME/.local/share/FreeCAD/Mod/MeshRound"
# The demo's files, so that the installed `meshround demo` runs without the source tree.
rm -rf "$MOD_DIR/resources"
mkdir -p "$MOD_DIR/resources/srail"
cp "$ROOT/resources/srail_demo.py" "$ROOT/resources/srail_render.py" "$ROOT/resources/render_support.py" "$MOD_DIR/resources/"
cp "$ROOT/resources/srail/srail_die.py" "$ROOT/resources/srail/README.md" "$MOD_DIR/resources/srail/"
# The `meshround` command line.
BIN_DIR="$HOME/.local/bin"
[ "$(id -u)" -eq 0 ] && BIN_DIR="/usr/local/bin"
mkdir -p "$BIN_DIR"
if [ -f "$MOD_DIR/meshround" ]; then
  chmod +x "$MOD_DIR/meshround"
  ln -sf "$MOD_DIR/meshround" "$BIN_DIR/meshround"
fi
echo "MeshRound built and installed into $MOD_DIR; the command line: $BIN_DIR/meshround"
case ":$PATH:" in *":$BIN_DIR:"*) ;; *) echo "(add $BIN_DIR to PATH to type just 'meshround')" ;; esac
