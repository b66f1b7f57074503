#!/usr/bin/env bash
# A change's cost, measured as performance.md's comparisons are: builds of
# one chapter at several commits side by side, their runs interleaved in
# rounds on the same device, so that drift (clocks, temperature, other
# load) falls on all of them alike. Prints; asserts nothing.
#   tools/ab.sh build DIR CHAPTER REV...
#       builds CHAPTER (e.g. 10_refraction) at each REV into DIR/<short rev>/:
#       the executable, its shaders and the scenes, relocatable, so DIR can be
#       carried to another machine (the GPU machine) and run there. Each REV
#       gets a git worktree and a Release build of the chapter alone (about a
#       minute each on 2 cores).
#   tools/ab.sh run DIR CHAPTER [--rounds N] [REV...] [-- CHAPTER ARGS...]
#       runs each build (all in DIR, or the REVs given) once per round with
#       --headless and the ARGS (default: --width 1920 --height 1080 --frames 60)
#       and prints each run's median GPU ms, then each build's median over rounds.
#       After a long load (10^6 spheres: seconds on the CPU, the GPU idle) the
#       first frames can run several times slower: give such scenes
#       --frames 300 (performance.md, "Short runs after a long load").
set -euo pipefail
usage() { sed -n '6,18p' "$0" >&2; exit 2; }
[ $# -ge 3 ] || usage
mode=$1 dir=$2 chapter=$3
shift 3
repo=$(cd "$(dirname "$0")/.." && pwd)
case "$mode" in
build)
  [ $# -ge 1 ] || usage
  mkdir -p "$dir/src"
  for rev in "$@"; do
    short=$(git -C "$repo" rev-parse --short "$rev")
    out="$dir/$short"
    [ -x "$out/$chapter" ] && { echo "$short: built already"; continue; }
    src="$dir/src/$short" build="$dir/src/build-$short"
    [ -d "$src" ] || git -C "$repo" worktree add --detach "$src" "$short" > /dev/null
    cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=OFF > "$dir/src/$short.log" 2>&1
    cmake --build "$build" -j"$(nproc)" --target "$chapter" >> "$dir/src/$short.log" 2>&1
    mkdir -p "$out/shaders" "$out/assets"
    cp "$build/bin/$chapter" "$out/"
    # all of them: chapter 12 runs chapter 11's ray generation shader
    cp -r "$build/bin/shaders/." "$out/shaders/"
    cp -r "$build/bin/assets/scenes" "$out/assets/"
    [ -f "$build/bin/assets/sky.png" ] && cp "$build/bin/assets/sky.png" "$out/assets/"
    # the meshes of chapters 12 and 13's scenes
    [ -d "$build/bin/assets/meshes" ] && cp -r "$build/bin/assets/meshes" "$out/assets/"
    echo "$short: $(git -C "$repo" log -1 --format=%s "$short" | cut -c1-70)"
  done
  echo "(git worktree prune after removing $dir/src)"
  ;;
run)
  rounds=3 revs=() args=()
  while [ $# -gt 0 ]; do
    case "$1" in
      --rounds) rounds=$2; shift ;;
      --) shift; args=("$@"); break ;;
      *) revs+=("$1") ;;
    esac
    shift
  done
  [ ${#args[@]} -gt 0 ] || args=(--width 1920 --height 1080 --frames 60)
  if [ ${#revs[@]} -eq 0 ]; then
    for exe in "$dir"/*/"$chapter"; do revs+=("$(basename "$(dirname "$exe")")"); done
  fi
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' EXIT
  for ((r = 1; r <= rounds; r++)); do
    for rev in "${revs[@]}"; do
      if "$dir/$rev/$chapter" --headless "${args[@]}" --output "$tmp/run.png" > "$tmp/log" 2>&1; then
        ms=$(python3 -c "import json; print('%.4f' % json.load(open('$tmp/run.json'))['gpu_ms']['median'])")
      else
        ms=failed; tail -2 "$tmp/log" >&2
      fi
      echo "round $r $rev $ms" | tee -a "$tmp/all"
    done
  done
  echo
  python3 - "$tmp/all" <<'PY'
import statistics, sys
times = {}
for line in open(sys.argv[1]):
    _, _, rev, ms = line.split()
    if ms != "failed":
        times.setdefault(rev, []).append(float(ms))
print("| build | median GPU ms over rounds | min | max |")
print("| --- | ---: | ---: | ---: |")
for rev, t in times.items():
    print(f"| {rev} | {statistics.median(t):.4f} | {min(t):.4f} | {max(t):.4f} |")
PY
  ;;
*) usage ;;
esac
