# rg_configure BUILD_DIR [CMAKE_ARGS...]: `cmake -S . -B BUILD_DIR` with the
# Ninja generator where ninja is installed and the folder is new (an existing
# build folder keeps its generator). Ninja compiles a target's files while
# the targets it depends on still link, which Make's generator does not: on
# 2 cores the sanitizer build takes 4 minutes instead of 6.
rg_configure() {
  local dir=$1 generator=()
  shift
  if [ ! -f "$dir/CMakeCache.txt" ] && command -v ninja >/dev/null; then
    generator=(-G Ninja)
  fi
  cmake -S . -B "$dir" "${generator[@]}" "$@" >/dev/null
}
