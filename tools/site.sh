#!/usr/bin/env bash
# Builds the docs site from docs/ into out/site/ (or --out DIR) with mkdocs
# --strict: a broken link, a missing image or a page left out of mkdocs.yml's
# nav fails the build. Prints the index.html to open (from disk or a server).
#   tools/site.sh [--out DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
out=out/site
while [ $# -gt 0 ]; do
  case "$1" in
    --out) out="$2"; shift ;;
    *) echo "site.sh: unknown argument $1 (usage: tools/site.sh [--out DIR])" >&2; exit 2 ;;
  esac
  shift
done
if ! command -v mkdocs >/dev/null; then
  echo "site.sh: mkdocs is not installed (Debian: mkdocs mkdocs-material python3-pymdownx libjs-katex; tools/setup.sh installs them)" >&2
  exit 1
fi
python3 tools/docs.py --check >&2 || { echo "site.sh: the code quoted in docs/ is stale" >&2; exit 1; }
log=$(mktemp); trap 'rm -f "$log"' EXIT
# mkdocs (Debian's, /usr/bin/mkdocs) runs on the system's Python 3.
if ! mkdocs build --strict --clean --site-dir "$out" >"$log" 2>&1; then
  grep -E "WARNING|ERROR|Error|Aborted" "$log" >&2 || cat "$log" >&2
  echo "site.sh: the site did not build" >&2
  exit 1
fi
echo "site: $(cd "$out" && pwd)/index.html"
