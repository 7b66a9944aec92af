#!/usr/bin/env bash
# The project's one entry point (the README's quick start calls it).
#   scripts/dev.sh demo   install what is missing, build, run the main job on the built-in default
#   scripts/dev.sh test      install what is missing, build, run the tests (C++, Python, Blender): ~4 minutes on 2 cores
#   scripts/dev.sh sanitize  the C++ tests again under AddressSanitizer and UBSan (CI runs it; ~15 minutes)
#   scripts/dev.sh build     install what is missing and build
#   scripts/dev.sh bench     build, then the benchmark suite (core and Blender) as one table: docs/benchmarks.md;
#                            `bench quick` for a short run, other arguments go to scripts/bench.py
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
build="$root/build"
jobs=$(nproc 2>/dev/null || echo 2)

# Debian 12 packages the build, the tests and the add-on need.
packages=(cmake g++ make libeigen3-dev libopenmesh-dev pybind11-dev python3-dev python3-pybind11 python3-numpy
          python3-pytest libpugixml-dev zlib1g-dev nlohmann-json3-dev libcli11-dev libgtest-dev blender time)

source "$root/scripts/install_missing.sh"

build() {
  install_missing "${packages[@]}"
  echo "== building (Release) in build/"
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$build" -j"$jobs"
}

demo() {
  build
  mkdir -p "$build/demo"
  echo "== main job: a synthetic arterial network, its graph, its surface, and a check of the surface"
  "$build/bin/vesselmesh" synth -o "$build/demo/network.vtk" --sections 2000 --loops 2 --seed 1
  "$build/bin/vesselmesh" info "$build/demo/network.vtk"
  "$build/bin/vesselmesh" mesh "$build/demo/network.vtk" -o "$build/demo/network.ply" --levels 2 \
    --stats-json "$build/demo/stats.json"
  "$build/bin/vesselmesh" check "$build/demo/network.ply" --centerline "$build/demo/network.vtk"

  echo "== the Blender add-on, installed into a fresh profile: the same network (millimetres), the lecture picture"
  rm -rf "$build/demo/blender-profile"
  BLENDER_USER_CONFIG="$build/demo/blender-profile/config" BLENDER_USER_SCRIPTS="$build/demo/blender-profile/scripts" \
    blender -b --factory-startup --python-exit-code 1 --python addon/examples/batch.py -- \
    --install "$build/vesselmesh.zip" --scale 0.001 --preset teaching \
    --render "$build/demo/network.png" --engine cycles --samples 128 --size 1280 800 \
    --export "$build/demo/surface" --format ply --blend "$build/demo/network.blend" \
    "$build/demo/network.vtk" | grep -v -E "EGL|^Fra:|^ *Time:|^$|^Saved:"  # render progress, GPU chatter
  echo "== the lecture picture: $build/demo/network.png (Teaching Render, Cycles); the surface with colours and"
  echo "   curvature values: $build/demo/surface/network.ply; the scene: $build/demo/network.blend"
}

run_tests() {
  build
  local failed=()
  echo "== C++ tests"
  ctest --test-dir "$build" --output-on-failure -j"$jobs" || failed+=("C++ tests")

  echo "== Python module tests (/usr/bin/python3)"
  VESSELMESH_PYTHON_PATH="$build/python" /usr/bin/python3 -m pytest -q native/python/tests || failed+=("Python tests")

  echo "== Blender tests (blender -b)"
  VESSELMESH_PYTHON_PATH="$build/python" blender -b --factory-startup --python-exit-code 1 \
    --python blend_tests/run.py -- -q blend_tests || failed+=("Blender tests")

  if [ ${#failed[@]} -gt 0 ]; then
    echo "FAILED: ${failed[*]}"
    exit 1
  fi
  echo "all test suites passed"
}

# Under the sanitizers the big-input timing prints and the shared-data surface suites (Shared…, …/SharedCohort, …/SharedSet: they
# only repeat the same code on larger inputs) would take most of an hour; they run in the Release build.
run_sanitized() {
  install_missing "${packages[@]}"
  echo "== C++ tests under AddressSanitizer and UBSan"
  cmake -S "$root" -B "$build/sanitize" -DCMAKE_BUILD_TYPE=Debug -DVESSELMESH_SANITIZE=ON \
        -DVESSELMESH_PYTHON=OFF >/dev/null
  cmake --build "$build/sanitize" -j"$jobs"
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    ctest --test-dir "$build/sanitize" --output-on-failure -j"$jobs" -E "^Shared|/Shared(Cohort|Set)|Timing|Million|PrintsTheTime"
  echo "sanitizer tests passed"
}

# The benchmark suite (scripts/bench.py says what it measures; docs/benchmarks.md has a full run's table).
bench() {
  build
  local args=()
  if [ "${1:-}" = quick ]; then args+=(--quick); shift; fi
  /usr/bin/python3 scripts/bench.py "${args[@]}" "$@"
}

case "${1:-}" in
  demo) demo ;;
  test) run_tests ;;
  sanitize) run_sanitized ;;
  build) build ;;
  bench) shift; bench "$@" ;;
  *) echo "usage: scripts/dev.sh demo|test|sanitize|build|bench [quick]" >&2; exit 2 ;;
esac
