#!/usr/bin/env bash
# Runs every built chapter headless with validation; each writes
# DIR/NN_name.png and DIR/NN_name.json. Prints one line per chapter and
# exits non-zero if any chapter failed.
#   tools/run-all.sh [--build DIR] [--out DIR] [chapter options...]
set -uo pipefail
cd "$(dirname "$0")/.."
build=build
out=out
extra=()
while [ $# -gt 0 ]; do
  case "$1" in
    --build) build="$2"; shift ;;
    --out) out="$2"; shift ;;
    *) extra+=("$1") ;;
  esac
  shift
done
mkdir -p "$out"
failed=0
printf '%-28s %-6s %-10s %-12s %-10s %s\n' chapter result size "gpu median" validation image
for exe in "$build"/bin/[0-9][0-9]_*; do
  [ -x "$exe" ] || continue
  name=$(basename "$exe")
  log="$out/$name.log"
  if "$exe" --headless --validation --output "$out/$name.png" "${extra[@]}" >"$log" 2>&1; then
    result=ok
  else
    result=FAIL; failed=1
  fi
  if [ -f "$out/$name.json" ]; then
    jq -r --arg r "$result" --arg img "$out/$name.png" \
      '[.chapter, $r, "\(.width)x\(.height)", "\(.gpu_ms.median * 1000 | round / 1000) ms", "\(.validation_messages) msgs", $img] | @tsv' \
      "$out/$name.json" | awk -F'\t' '{ printf "%-28s %-6s %-10s %-12s %-10s %s\n", $1, $2, $3, $4, $5, $6 }'
  else
    printf '%-28s %-6s (no report; see %s)\n' "$name" "$result" "$log"
  fi
  [ "$result" = ok ] || tail -n 3 "$log" | sed 's/^/    /'
done
exit $failed
