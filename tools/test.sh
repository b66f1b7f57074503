#!/usr/bin/env bash
# The whole test suite: installs what is missing, builds, runs ctest
# (every chapter on the Vulkan device there is, lavapipe in CI, with the
# validation layer on; the windowed tests under Xvfb).
#   tools/test.sh [ctest options, e.g. -L 04]
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh --deps-only
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc)"
ctest --test-dir build -j "$(nproc)" --output-on-failure "$@"
