#!/usr/bin/env bash
# The whole test suite: installs what is missing, builds (a compiler warning
# fails the suite), runs the sanitizer pass (tools/sanitize.sh: ASan + UBSan
# build, unit tests, scene fuzzing and every chapter) and then ctest (every
# chapter on the Vulkan device there is, lavapipe in CI, with the validation
# layer on; the windowed tests under Xvfb; the docs checks), and prints the
# ten slowest tests.
#
#   tools/test.sh [--system] [CTEST_ARGS...]
#
# --system: only the tests labelled `system`, those whose result depends on
# the system's compiler, libraries, validation layer and X server (CI's
# Debian 13 part). Extra arguments go to ctest (e.g. -L 04); with any, or
# with --system, the sanitizer pass is skipped (RG_SANITIZE=1 forces it,
# RG_SANITIZE=0 skips it). RG_TEST_TIME_SCALE (default: one plus the load
# per core when the suite starts) multiplies every test's time limit.
set -euo pipefail
cd "$(dirname "$0")/.."
system=0
if [ "${1:-}" = "--system" ]; then
  system=1; shift
fi
setup_args=(--deps-only)
[ "$system" -eq 0 ] || setup_args+=(--no-docs)
tools/setup.sh "${setup_args[@]}"

if [ -z "${RG_TEST_TIME_SCALE:-}" ]; then
  RG_TEST_TIME_SCALE=$(awk -v cores="$(nproc)" '{ s = 1 + $1 / cores; printf "%.1f", s }' /proc/loadavg)
fi
export RG_TEST_TIME_SCALE
echo "== test time scale: $RG_TEST_TIME_SCALE (RG_TEST_TIME_SCALE)"

took() { echo "== $1 took $(((SECONDS - $2) / 60)) min $(((SECONDS - $2) % 60)) s"; }
. tools/lib/configure.sh  # rg_configure
start=$SECONDS
rg_configure build -DCMAKE_BUILD_TYPE=Release
status=0
targets=()
[ "$system" -eq 0 ] || targets=(--target system_tests)
cmake --build build -j "$(nproc)" "${targets[@]}" 2>&1 | tee build/build.log || status=1
# A clean build (CI's) prints no warning; an incremental one shows only the
# files it compiled again.
if grep -E "warning:|WARNING:" build/build.log >/dev/null; then
  echo "== FAILED: the build printed $(grep -cE "warning:|WARNING:" build/build.log) warning(s):"
  grep -E "warning:|WARNING:" build/build.log | sort -u | sed -n 1,20p
  status=1
fi
[ "$status" -eq 0 ] || exit 1
took "the build" "$start"

sanitize=${RG_SANITIZE:-$([ $# -eq 0 ] && [ "$system" -eq 0 ] && echo 1 || echo 0)}
if [ "$sanitize" = 1 ]; then
  start=$SECONDS
  tools/sanitize.sh || status=1
  took "the sanitizer pass" "$start"
fi
start=$SECONDS
ctest_args=("$@")
[ "$system" -eq 0 ] || ctest_args=(-L "$(cat build/system_labels.txt)" -LE '^docs$' "$@")
ctest --test-dir build -j "$(nproc)" --output-on-failure "${ctest_args[@]}" 2>&1 | tee build/ctest.log ||
  status=1
took ctest "$start"
echo "== the ten slowest tests"
# sed reads to the end, where head would quit early and leave sort a broken
# pipe (a failure under pipefail)
grep -E "^ *[0-9]+/[0-9]+ Test +#" build/ctest.log | sed -E 's/^ *[0-9]+\/[0-9]+ Test +#[0-9]+: //' |
  awk '{ printf "%8.1f s  %s\n", $(NF - 1), $1 }' | sort -rn | sed -n 1,10p
exit $status
