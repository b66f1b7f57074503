#!/usr/bin/env bash
# Installs what is missing (Debian 12 or 13), builds RayGlass, runs every
# chapter headless with validation, writing each chapter's PNG and JSON
# report into one folder (default: out/) and printing one line per chapter,
# builds the docs site into out/site/ (tools/site.sh) and prints it as the
# ebook out/rayglass.pdf (tools/ebook.py). It builds the chapters only;
# tools/test.sh builds the tests.
#
#   tools/setup.sh [--deps-only] [--no-docs] [--size WxH] [--out DIR] [--build DIR]
#
# --no-docs leaves out the site, the ebook, the glTF validator (one test of
# the full suite) and the packages only they need (CI's Debian 13 part).
# --size renders the chapters' pictures at W x H instead of each chapter's
# default (800x450); CI's Debian 13 part checks them smaller. Each step
# prints the time it took.
# Idempotent: installed packages are skipped. Uses sudo when not root.
set -euo pipefail
cd "$(dirname "$0")/.."

deps_only=0
docs=1
out=out
build=build
size=()
while [ $# -gt 0 ]; do
  case "$1" in
    --deps-only) deps_only=1 ;;
    --no-docs) docs=0 ;;
    --out) out="$2"; shift ;;
    --build) build="$2"; shift ;;
    --size)
      [[ "${2:-}" =~ ^([0-9]+)x([0-9]+)$ ]] || { echo "setup.sh: --size wants WxH, e.g. 400x225" >&2; exit 2; }
      size=(--width "${BASH_REMATCH[1]}" --height "${BASH_REMATCH[2]}"); shift ;;
    *) echo "setup.sh: unknown argument $1" >&2; exit 2 ;;
  esac
  shift
done

packages=(cmake g++ make ninja-build pkg-config jq libvulkan-dev vulkan-validationlayers glslang-tools libglfw3-dev libx11-dev
          libglm-dev libstb-dev nlohmann-json3-dev libcli11-dev libgtest-dev xvfb xauth gnuplot-nox python3
          libimgui-dev xdotool libtinygltf-dev libtinyobjloader-dev python3-pil python3-numpy)
# the site, its browser tests, the ebook and the glTF validator
docs_packages=(mkdocs mkdocs-material python3-pymdownx libjs-katex chromium chromium-driver python3-selenium
               poppler-utils fonts-dejavu-core nodejs)
[ "$docs" -eq 0 ] || packages+=("${docs_packages[@]}")
# The Khronos glTF validator (a test runs it on every glTF file the project
# writes): from the npm registry into .node/, a pinned version.
gltf_validator=gltf-validator@2.0.0-dev.3.10
min_mesa=24.1

sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)

need_what() {
  echo "RayGlass needs: a C++20 compiler, CMake >= 3.22, the Vulkan loader and headers, glslangValidator,"
  echo "GLFW 3.3 or 3.4, GLM, stb, nlohmann-json, CLI11, GoogleTest, Dear ImGui 1.86 to 1.91 (the overlay), Xvfb and xdotool (window tests),"
  echo "mkdocs with mkdocs-material, pymdownx and KaTeX (the docs site), Chromium + chromedriver + selenium (its tests),"
  echo "and a Vulkan driver with VK_KHR_ray_tracing_pipeline (no GPU: Mesa lavapipe >= $min_mesa)."
}

mesa_version() { dpkg-query -W -f='${Version}' mesa-vulkan-drivers 2>/dev/null || true; }
mesa_ok() {
  local v; v=$(mesa_version)
  [ -n "$v" ] && dpkg --compare-versions "$v" ge "$min_mesa"
}
# The release's own candidate, before any backports suite is added.
release_mesa_ok() {
  local v; v=$(apt-cache policy mesa-vulkan-drivers 2>/dev/null | awk '$1 == "Candidate:" { print $2 }')
  [ -n "$v" ] && [ "$v" != "(none)" ] && dpkg --compare-versions "$v" ge "$min_mesa"
}

. tools/lib/apt-source.sh  # debian_uri

install_deps() {
  if ! command -v dpkg >/dev/null || [ ! -f /etc/debian_version ]; then
    echo "setup.sh: this is not a Debian system; install these yourself, then run cmake:" >&2
    need_what >&2
    exit 1
  fi
  local missing=() p
  for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ ${#missing[@]} -gt 0 ] || ! mesa_ok; then
    export DEBIAN_FRONTEND=noninteractive
    "${sudo_cmd[@]}" apt-get update -q
  fi
  if [ ${#missing[@]} -gt 0 ]; then
    echo "== installing: ${missing[*]}"
    "${sudo_cmd[@]}" apt-get install -y -q "${missing[@]}"
  fi
  if ! mesa_ok && release_mesa_ok; then
    # Debian 13's own Mesa (25.0) has lavapipe with ray tracing.
    echo "== installing mesa-vulkan-drivers"
    "${sudo_cmd[@]}" apt-get install -y -q mesa-vulkan-drivers
  fi
  if ! mesa_ok; then
    # Debian 12's own Mesa (22.3) has no ray tracing in lavapipe; the
    # release's backports suite has a newer one. Same archive, suite
    # <codename>-backports, taken from the system's existing source.
    . /etc/os-release
    local codename=${VERSION_CODENAME:-}
    local uri; uri=$(debian_uri "$codename" || true)
    if [ -z "$codename" ] || [ -z "$uri" ]; then
      echo "setup.sh: cannot find this system's Debian apt source to derive $codename-backports from." >&2
      echo "Install mesa-vulkan-drivers >= $min_mesa (Debian: from <codename>-backports) or a GPU driver with ray tracing." >&2
      exit 1
    fi
    local list=/etc/apt/sources.list.d/rayglass-backports.sources
    if ! grep -qs "$codename-backports" /etc/apt/sources.list /etc/apt/sources.list.d/* ; then
      echo "== adding $codename-backports from $uri"
      printf 'Types: deb\nURIs: %s\nSuites: %s-backports\nComponents: main\nSigned-By: /usr/share/keyrings/debian-archive-keyring.gpg\n' \
        "$uri" "$codename" | "${sudo_cmd[@]}" tee "$list" >/dev/null
      "${sudo_cmd[@]}" apt-get update -q
    fi
    echo "== installing mesa-vulkan-drivers from $codename-backports"
    "${sudo_cmd[@]}" apt-get install -y -q -t "$codename-backports" mesa-vulkan-drivers
    if ! mesa_ok; then
      echo "setup.sh: mesa-vulkan-drivers is $(mesa_version), RayGlass needs >= $min_mesa." >&2
      exit 1
    fi
  fi
}

step=$SECONDS
took() { echo "== $1 took $((SECONDS - step)) s"; step=$SECONDS; }
install_deps
took "installing the packages"
if [ "$docs" -eq 1 ] && [ ! -f .node/node_modules/gltf-validator/package.json ]; then
  # Debian's npm, unless a Node.js from elsewhere brought its own
  command -v npm >/dev/null || "${sudo_cmd[@]}" apt-get install -y -q npm
  echo "== npm: $gltf_validator into .node/"
  # offline, the rest still installs; the one test that needs it says so
  npm install --prefix .node --no-audit --no-fund --loglevel=error "$gltf_validator" >/dev/null ||
    echo "setup.sh: warning: npm could not install $gltf_validator (the gltf_validator test will fail)" >&2
  took "npm"
fi
[ "$deps_only" -eq 1 ] && exit 0

echo "== building the chapters in $build"
. tools/lib/configure.sh  # rg_configure
rg_configure "$build" -DCMAKE_BUILD_TYPE=Release
cmake --build "$build" -j "$(nproc)" --target chapters
took "the build"

status=0
tools/run-all.sh --build "$build" --out "$out" "${size[@]}" || status=1
took "running the chapters"
[ "$docs" -eq 1 ] || exit $status
echo "== building the docs site"
tools/site.sh --out "$out/site" || status=1
took "the site"
echo "== printing the ebook"
/usr/bin/python3 tools/ebook.py --site "$out/site" --out "$out/rayglass.pdf" || status=1
took "the ebook"
exit $status
