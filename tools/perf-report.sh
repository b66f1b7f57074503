#!/usr/bin/env bash
# The speed-versus-error report: measures on this machine's Vulkan device
# into docs/perf/<device>/, plots with gnuplot, and rebuilds
# docs/performance.md from every device measured so far.
#   tools/perf-report.sh [--build DIR] [perf_report options...]
#   tools/perf-report.sh --assemble-only      (plots and page from existing data)
# The scaling study is tools/scaling.py (--out docs/perf/<device>), run apart:
# it takes minutes on lavapipe; this script plots and includes its results.
# So are chapter 04's antialiasing, tools/antialias_study.py, chapter 12's,
# tools/meshes_study.py, chapter 13's, tools/real_glass_study.py, and
# chapter 14's, tools/caustics_study.py, and chapter 15's,
# tools/frosted_study.py (the same --out).
# Results from another machine (bin/perf_report --bin bin --out DIR there):
# copy DIR to docs/perf/<device>/ and run with --assemble-only.
set -euo pipefail
cd "$(dirname "$0")/.."
build=build; assemble_only=0; args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --build) build="$2"; shift ;;
    --assemble-only) assemble_only=1 ;;
    *) args+=("$1") ;;
  esac
  shift
done
if [ $assemble_only -eq 0 ]; then
  # Measured into a scratch folder first: the device's name, which names
  # its folder under docs/perf/, is in the report the chapters write.
  scratch=$(mktemp -d)
  trap 'rm -rf "$scratch"' EXIT
  "$build"/bin/perf_report --bin "$build"/bin --out "$scratch" "${args[@]}"
  device=$(jq -r '.device' "$scratch/perf.json")
  slug=$(echo "$device" | tr 'A-Z' 'a-z' | sed 's/[^a-z0-9]\+/-/g; s/^-//; s/-$//' | cut -c1-40)
  out=docs/perf/$slug
  mkdir -p "$out"
  cp "$scratch"/perf.json "$scratch"/perf.md "$scratch"/convergence.dat "$out"/  # not runs/: each run's logs and images
  echo "measured $device into $out"
fi
page=docs/performance.md
# One measured section of a device: its table (TABLE.md), then the plot
# tools/plot_NAME.gp draws from NAME.dat, with a caption.
section() {
  local dir=$1 slug=$2 table=$3 name=$4 caption=$5
  local plot=docs/images/perf_${slug}_$name.png
  gnuplot -e "data='$dir/$name.dat'; out='$plot'; device='$slug'" "tools/plot_$name.gp"
  cat "$dir/$table.md"
  echo
  echo "![$caption, $slug](images/$(basename "$plot"))"
  echo
}
{
  echo "# Performance: speed against error"
  echo
  echo "Made by \`tools/perf-report.sh\` (which runs \`perf_report\`, \`tools/perf_report.cpp\`) on each device;"
  echo "the raw numbers are in \`docs/perf/<device>/perf.json\`. Benchmarks print, they never fail a test."
  echo
  for dir in docs/perf/*/; do
    slug=$(basename "$dir")
    if [ -f "$dir/perf.md" ]; then
      section "$dir" "$slug" perf convergence "Chapter 11: RMSE against accumulated samples, samples per hit and GPU time"
      if [ -f "$dir/scaling.md" ]; then  # tools/scaling.py
        section "$dir" "$slug" scaling scaling "GPU ms per frame and structure memory against the number of spheres"
      fi
    elif [ -f "$dir/meshes.json" ]; then  # a device measured for the chapter studies only
      echo "### $(jq -r '.device' "$dir/meshes.json")"
      echo
      echo "Driver: $(jq -r '.driver' "$dir/meshes.json"). Only the chapter studies below" \
           "(\`tools/antialias_study.py\` for 04, \`tools/meshes_study.py\` for 12," \
           "\`tools/real_glass_study.py\` for 13)."
      echo
    fi
    # tools/antialias_study.py, meshes_study.py, real_glass_study.py, caustics_study.py,
    # frosted_study.py; then each one's runs of another configuration (--tag T: STUDY-T.md)
    for study in antialias meshes real_glass caustics frosted; do
      for table in "$dir/$study.md" "$dir/$study"-*.md; do
        if [ -f "$table" ]; then
          cat "$table"
          echo
        fi
      done
    done
  done
  [ -f docs/perf/notes.md.in ] && cat docs/perf/notes.md.in
} > "$page"
echo "wrote $page"
