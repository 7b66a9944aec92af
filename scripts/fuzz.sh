#!/usr/bin/env bash
# Builds the libFuzzer targets (native/fuzz) with clang in build/fuzz and runs each in turn from its seeds
# with its dictionary. Fails on any crash, timeout or out-of-memory; prints per target the executions,
# the coverage (cov: edges, ft: features) and the corpus size. docs/fuzzing.md says more.
#   scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]   (default 30 s; targets swc vtk vtp csv pipeline)
# Environment: FUZZ_TIMEOUT (s per input, default 10), FUZZ_RSS_MB (default 2048), FUZZ_EXTRA (folders
# of extra seed files, space-separated: e.g. ../shared/data/brava-records, used in place, never copied
# into the repository), FUZZ_SEED (libFuzzer's random seed: the same inputs in the same order on every run
# from an empty corpus, as CI runs them; default a new seed each run), FUZZ_ARGS (more libFuzzer flags);
# others reach the targets (FUZZ_VERBOSE=1).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
build="$root/build/fuzz"
seconds=${1:-30}
[ $# -gt 0 ] && shift
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(swc vtk vtp csv pipeline)
timeout=${FUZZ_TIMEOUT:-10}
rss_mb=${FUZZ_RSS_MB:-2048}
jobs=$(( $(nproc 2>/dev/null || echo 2) < 2 ? 1 : 2 ))  # other work shares the machine

packages=(clang-14 libclang-rt-14-dev cmake make libeigen3-dev libpugixml-dev zlib1g-dev nlohmann-json3-dev
          libcli11-dev)

source "$root/scripts/install_missing.sh"

# The project's own test fixtures as extra seeds, in the form each target reads.
fixtures() {
  local target=$1 dir="$build/fixtures/$1" data="$root/native/tests/data"
  rm -rf "$dir"
  mkdir -p "$dir"
  case "$target" in
    swc | vtk | vtp) cp "$data"/*."$target" "$dir"/ 2>/dev/null || true ;;
    csv) { cat "$data/y_vertices.csv"; printf '\0'; cat "$data/y_edges.csv"; } > "$dir/y.csv" ;;
    pipeline)  # SWC mode (byte 0 bit 0), levels 1 (bit 1)
      for f in "$data"/*.swc; do { printf '\003'; cat "$f"; } > "$dir/$(basename "$f").bin"; done ;;
  esac
  echo "$dir"
}

install_missing "${packages[@]}"
for t in "${targets[@]}"; do
  [ -f "$root/native/fuzz/fuzz_$t.cpp" ] || { echo "unknown fuzz target '$t'" >&2; exit 2; }
done
echo "== configuring and building (clang-14, libFuzzer, ASan, UBSan) in build/fuzz"
CC=clang-14 CXX=clang++-14 cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVESSELMESH_FUZZ=ON \
  -DVESSELMESH_PYTHON=OFF -DVESSELMESH_TESTS=OFF >/dev/null
cmake --build "$build" -j"$jobs" --target "${targets[@]/#/fuzz_}" >/dev/null

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
failed=()
printf '%-9s %-7s %12s %8s %8s %8s %10s  %s\n' target result executions exec/s cov ft corpus "corpus size"
for t in "${targets[@]}"; do
  corpus="$build/corpus/$t" artifacts="$build/artifacts/$t" log="$build/logs/$t.log"
  mkdir -p "$corpus" "$artifacts" "$(dirname "$log")"
  seeds=("$root/native/fuzz/seeds/$t" "$(fixtures "$t")")
  for extra in ${FUZZ_EXTRA:-}; do seeds+=("$extra"); done
  rc=0
  # shellcheck disable=SC2086
  "$build/bin/fuzz_$t" -max_total_time="$seconds" -timeout="$timeout" -rss_limit_mb="$rss_mb" \
    -dict="$root/native/fuzz/$t.dict" -artifact_prefix="$artifacts/" -print_final_stats=1 \
    ${FUZZ_SEED:+-seed=$FUZZ_SEED} ${FUZZ_ARGS:-} \
    "$corpus" "${seeds[@]}" > "$log" 2>&1 || rc=$?
  # The last status line: "#N DONE cov: C ft: F corp: U/S lim: ... exec/s: E rss: ...".
  status=$(grep -E '^#[0-9]+' "$log" | tail -1 || true)
  field() { sed -n "s/.* $1: \([^ ]*\).*/\1/p" <<<"$status"; }
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  speed=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")
  corp=$(field corp)
  result=ok
  if [ $rc -ne 0 ]; then
    result=FAILED
    failed+=("$t")
  fi
  printf '%-9s %-7s %12s %8s %8s %8s %10s  %s\n' "$t" "$result" "${runs:-?}" "${speed:-?}" "$(field cov)" \
    "$(field ft)" "${corp%%/*}" "${corp#*/}"
  if [ $rc -ne 0 ]; then
    grep -E 'ERROR:|SUMMARY:|runtime error|terminate called|what\(\)' "$log" | head -5 | sed 's/^/    /'
    grep -E 'Test unit written to|artifact_prefix' "$log" | sed 's/^/    /'
    echo "    full log: ${log#"$root"/}"
  fi
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "FAILED: ${failed[*]} (reproduce: build/fuzz/bin/fuzz_<target> <artifact>)"
  exit 1
fi
echo "all fuzz targets ran clean"
