#!/usr/bin/env bash
# The sanitizer pass of the test suite (tools/test.sh runs it). Builds the
# chapters and the CPU-only tests with AddressSanitizer and
# UndefinedBehaviorSanitizer (-DRG_SANITIZE=ON) in their own folder, then
# runs the unit tests, the scene and mesh fuzz cases through the loaders, and every
# chapter headless at a small size with the validation layer on. Any
# sanitizer report, validation message or non-zero exit fails the pass.
# Leaks inside libraries that are not RayGlass's are suppressed by
# tools/sanitizers.supp, which gives the reason for each entry.
#   tools/sanitize.sh [--build DIR]
set -uo pipefail
cd "$(dirname "$0")/.."
build=build-asan
[ "${1:-}" = "--build" ] && build="$2"

chapters=(01_vulkan_setup 02_synchronization 03_acceleration_structures 04_raygen_miss 05_ambient 06_diffuse
          07_specular 08_reflection 09_fresnel 10_refraction 11_rough 12_triangle_meshes 13_real_glass
          14_caustics 15_frosted_glass)
units=(test_sphere_intersection test_sbt test_fresnel test_sampling test_scene_fuzz test_faults test_12_triangle_meshes)
# -Og: GCC compiles the instrumented code in two thirds of -O1's time
# (shared/core/cli.cpp: 13.7 s against 20.3 s; -O0 10.7 s, but the fuzz
# and the CPU references then ran three times slower than at -O1).
echo "== sanitizer build in $build (ASan + UBSan, -Og)"
. tools/lib/configure.sh  # rg_configure
rg_configure "$build" -DCMAKE_BUILD_TYPE=Sanitize -DCMAKE_CXX_FLAGS_SANITIZE="-Og -g1" -DRG_SANITIZE=ON ||
  exit 1
cmake --build "$build" -j "$(nproc)" --target "${chapters[@]}" "${units[@]}" >"$build/sanitize-build.log" 2>&1 ||
  { tail -n 30 "$build/sanitize-build.log"; exit 1; }
if grep -q "warning:" "$build/sanitize-build.log"; then
  echo "FAILED: the sanitizer build printed warnings:"; grep "warning:" "$build/sanitize-build.log" | sort -u | head -n 20
  exit 1
fi

export ASAN_OPTIONS="detect_leaks=1:halt_on_error=1:exitcode=23"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:exitcode=23"
export LSAN_OPTIONS="suppressions=$PWD/tools/sanitizers.supp:print_suppressions=0"
# The Vulkan loader unloads the driver and the layer when the instance is
# destroyed, before LSan looks at the heap, which leaves their leaks without
# a name. Preloaded, they stay loaded and LSan can attribute them. ASan's
# runtime must come first.
preload="$(gcc -print-file-name=libasan.so)"
for lib in libvulkan_lvp.so libVkLayer_khronos_validation.so; do
  path=$(ldconfig -p | awk -v l="$lib" '$1 == l { print $NF; exit }')
  [ -n "$path" ] && preload="$preload $path"
done

out="$build/sanitize-output"
rm -rf "$out"; mkdir -p "$out"
passed=0; failed=0
judge() {  # name, exit status: its log must hold no report
  local name=$1 status=$2
  if [ "$status" -eq 0 ] && ! grep -qE "runtime error|ERROR: (Address|Leak)Sanitizer|validation message" "$out/$name.log"; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1))
    echo "FAILED $name (log: $out/$name.log)"
    grep -E -m 5 -A 8 "runtime error|ERROR: |validation" "$out/$name.log" | head -n 40
  fi
}
check() {  # name, command...
  local name=$1 status=0; shift
  "$@" >"$out/$name.log" 2>&1 || status=$?
  judge "$name" "$status"
}
# The loaders' fuzz runs on one core (up to a minute) beside the rest.
(env RG_FUZZ_STRIDE=3 RG_FUZZ_SECONDS=60 "$build/bin/test_scene_fuzz" --gtest_filter='*Loader*' \
   >"$out/test_scene_fuzz.log" 2>&1; echo $? >"$out/test_scene_fuzz.status") &
fuzz=$!
for t in test_sphere_intersection test_sbt test_fresnel test_sampling; do check "$t" "$build/bin/$t"; done
# Chapter 12's mesh loader and reference (the fuzzed mesh files, the checks,
# textures, the watertight and optics tests); its GPU runs are the chapter's
# line below, so the optics read off rendered images are left to ctest.
check test_12_meshes "$build/bin/test_12_triangle_meshes" \
  --gtest_filter='Meshes.Fuzzed*:Meshes.Broken*:Meshes.Open*:Meshes.Degenerate*:Meshes.Gltf*:Meshes.Generated*:Optics.*:Textures.Gltf*:Textures.Obj*:Textures.Reference*-Optics.*FromTheImage'
# The fault suite (signals, a full disk, special files, limits): its chapters
# run sanitized too, and any report breaks their one line of stderr. Not its
# window test: with the layer preloaded GLFW finds no Vulkan surface support
# (the chapters above run headless for the same reason).
check test_faults env LD_PRELOAD="$preload" "$build/bin/test_faults" --gtest_filter='-Window.*'
for c in "${chapters[@]}"; do
  args=(--headless --validation --width 64 --height 36 --frames 2 --output "$out/$c.png")
  [ "${c%%_*}" -ge 4 ] && args+=(--reference)
  # a small photon map and reference (the sanitized reference is slow)
  [ "$c" = 14_caustics ] || [ "$c" = 15_frosted_glass ] && args+=(--photons 4000 --reference-photons 64)
  check "$c" env LD_PRELOAD="$preload" "$build/bin/$c" "${args[@]}"
done
wait "$fuzz"
judge test_scene_fuzz "$(cat "$out/test_scene_fuzz.status")"
echo "sanitizers: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
