#!/usr/bin/env bash
# Benchmark: runs each built ray tracing chapter headless at a size (default
# 640x360) for N frames and prints a table of GPU time and ray throughput
# from the chapters' own reports (timestamp queries). Prints; asserts nothing.
#   tools/bench.sh [--build DIR] [--width W] [--height H] [--frames N] [chapter-prefix...]
set -euo pipefail
cd "$(dirname "$0")/.."
build=build; width=640; height=360; frames=30; only=()
while [ $# -gt 0 ]; do
  case "$1" in
    --build) build="$2"; shift ;;
    --width) width="$2"; shift ;;
    --height) height="$2"; shift ;;
    --frames) frames="$2"; shift ;;
    *) only+=("$1") ;;
  esac
  shift
done
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
first=1
for exe in "$build"/bin/[0-9][0-9]_*; do
  name=$(basename "$exe")
  nn=${name%%_*}
  [ "$nn" -ge 3 ] 2>/dev/null || continue
  if [ ${#only[@]} -gt 0 ]; then
    keep=0; for o in "${only[@]}"; do [[ $name == $o* ]] && keep=1; done
    [ $keep -eq 1 ] || continue
  fi
  "$exe" --headless --width "$width" --height "$height" --frames "$frames" --output "$out/$name.png" >/dev/null 2>&1 ||
    { echo "$name: failed" >&2; continue; }
  if [ $first -eq 1 ]; then
    jq -r '"device: \(.device)\ndriver: \(.driver)"' "$out/$name.json"
    echo "size: ${width}x${height}, $frames frames, $(date -u +%Y-%m-%d)"
    echo
    printf '| %-28s | %10s | %10s | %10s | %14s | %10s |\n' chapter "median ms" "min ms" "max ms" "rays/frame" "Mrays/s"
    printf '|%s|%s|%s|%s|%s|%s|\n' "------------------------------" "------------" "------------" "------------" "----------------" "------------"
    first=0
  fi
  jq -r '[.chapter, .gpu_ms.median, .gpu_ms.min, .gpu_ms.max, (.rays_per_frame // "-"), (.mrays_per_s // "-")] | @tsv' "$out/$name.json" |
    awk -F'\t' '{ printf "| %-28s | %10.3f | %10.3f | %10.3f | %14s | %10s |\n", $1, $2, $3, $4, $5, ($6 == "-" ? "-" : sprintf("%.1f", $6)) }'
done
