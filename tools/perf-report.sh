#!/usr/bin/env bash
# The speed-versus-error report: measures on this machine's Vulkan device
# into docs/perf/<device>/, plots with gnuplot, and rebuilds
# docs/performance.md from every device measured so far.
#   tools/perf-report.sh [--build DIR] [perf_report options...]
#   tools/perf-report.sh --assemble-only      (plots and page from existing data)
# The scaling study is tools/scaling.py (--out docs/perf/<device>), run apart:
# it takes minutes on lavapipe; this script plots and includes its results.
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
  device=$(vulkaninfo --summary 2>/dev/null | awk -F'= ' '/deviceName/ {print $2; exit}')
  slug=$(echo "${device:-device}" | tr 'A-Z' 'a-z' | sed 's/[^a-z0-9]\+/-/g; s/^-//; s/-$//' | cut -c1-40)
  out=docs/perf/$slug
  "$build"/bin/perf_report --bin "$build"/bin --out "$out" "${args[@]}"
  rm -rf "$out/runs"  # logs and images of each run: not kept
fi
page=docs/performance.md
{
  echo "# Performance: speed against error"
  echo
  echo "Made by \`tools/perf-report.sh\` (which runs \`perf_report\`, \`tools/perf_report.cpp\`) on each device;"
  echo "the raw numbers are in \`docs/perf/<device>/perf.json\`. Benchmarks print, they never fail a test."
  echo
  for dir in docs/perf/*/; do
    [ -f "$dir/perf.md" ] || continue
    slug=$(basename "$dir")
    plot=docs/images/perf_${slug}_convergence.png
    gnuplot -e "data='$dir/convergence.dat'; out='$plot'; device='$slug'" tools/plot_convergence.gp
    cat "$dir/perf.md"
    echo
    echo "![Chapter 11: RMSE against accumulated samples, samples per hit and GPU time, $slug](images/$(basename "$plot"))"
    echo
    if [ -f "$dir/scaling.md" ]; then  # tools/scaling.py
      scaling=docs/images/perf_${slug}_scaling.png
      gnuplot -e "data='$dir/scaling.dat'; out='$scaling'; device='$slug'" tools/plot_scaling.gp
      cat "$dir/scaling.md"
      echo
      echo "![GPU ms per frame and structure memory against the number of spheres, $slug](images/$(basename "$scaling"))"
      echo
    fi
  done
  [ -f docs/perf/notes.md.in ] && cat docs/perf/notes.md.in
} > "$page"
echo "wrote $page"
