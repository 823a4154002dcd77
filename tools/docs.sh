#!/bin/bash
# Build the HTML manual (doc/: the style pages, the theory page, the reports) with Debian's
# Sphinx, warnings as errors.  Usage: bash tools/docs.sh [output folder, default build/html]
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$here/build/html}
/usr/bin/python3 -c "import sphinx, myst_parser" 2>/dev/null ||
  { echo "docs.sh: needs python3-sphinx and python3-myst-parser (bash tools/setup.sh installs them)" >&2; exit 1; }
/usr/bin/python3 -m sphinx -W --keep-going -q -b html "$here/doc" "$out"
echo "docs.sh: open $out/index.html"
