#!/usr/bin/env bash
# From a fresh machine to a rounded S-rail die: installs, builds, installs the workbench, runs the demo.
# Results land in out/ (STL, OBJ, FCStd, JSON report, PNG).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$ROOT/tools/setup.sh"
cd "$ROOT"
/usr/bin/python3 resources/srail_demo.py "${1:-out}"
