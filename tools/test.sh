#!/usr/bin/env bash
# The whole test suite: installs what is missing, builds, runs the sanitizer
# pass (tools/sanitize.sh: ASan + UBSan build, unit tests, scene fuzzing and
# every chapter) and then ctest (every chapter on the Vulkan device there is,
# lavapipe in CI, with the validation layer on; the windowed tests under Xvfb;
# the docs checks). Extra arguments go to ctest (e.g. -L 04); with any,
# the sanitizer pass is skipped (RG_SANITIZE=1 forces it, RG_SANITIZE=0 skips it).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh --deps-only
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc)"
sanitize=${RG_SANITIZE:-$([ $# -eq 0 ] && echo 1 || echo 0)}
status=0
if [ "$sanitize" = 1 ]; then
  tools/sanitize.sh || status=1
fi
ctest --test-dir build -j "$(nproc)" --output-on-failure "$@" || status=1
exit $status
