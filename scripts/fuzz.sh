#!/usr/bin/env bash
# Builds and runs the libFuzzer targets of fuzz/ (one per parser: CARMEN text
# and files, ROS1 bag structure and whole bags, ROS 2 bags (MCAP, SQLite,
# metadata.yaml, whole bags) and CDR messages, swarm network messages, .dsmap
# and its payload, scenario YAML, config JSON, TUM, relations, PGM) under
# ASan + UBSan with leak detection, then prints a table: target, executions,
# corpus size, crashes.
#
#   scripts/fuzz.sh --smoke               every target for 8 s (CI: scripts/test.sh)
#   scripts/fuzz.sh --runs 1000000        the long runs: 10^6 executions per target
#   scripts/fuzz.sh --time 600 dsmap tum  the named targets for 10 minutes each
#   scripts/fuzz.sh --make-corpus         regenerate fuzz/corpus/* and fuzz/dict/*
# Options: --build DIR (default build-fuzz; configured with clang and
# -DDSSWARM_FUZZ=ON unless DIR is configured already), --jobs N (targets run
# at once; default 1, --smoke: nproc), --no-build.
#
# A crash, sanitizer report, leak, hang (an input running over 10 s) or
# out-of-memory (over 2 GB) stops its target, saves the input under
# DIR/fuzz-artifacts/TARGET/ (crash-*, leak-*, timeout-*, oom-*), prints the
# end of the target's log (the report; a small input in Base64) and makes the
# script exit 1. Reproduce with `DIR/fuzz/TARGET FILE`; every such input
# becomes a unit test beside its parser. New inputs that reach new code go to
# DIR/fuzz-corpus/TARGET (kept between runs, never committed); the committed
# seeds in fuzz/corpus/TARGET are only read. The seeds are the unit tests'
# inputs and excerpts of ../shared/data: --make-corpus needs that data for the
# excerpts.
#
# Adding a target for a new parser (a network message, say):
#   1. fuzz/NAME.cpp: LLVMFuzzerTestOneInput hands the bytes to the parser
#      through fuzz::expect_clean<InputError>(source, ...), and
#      dsswarm::fuzz::write_seeds writes its seeds and dictionary (fuzz/tum.cpp
#      is the smallest example, fuzz/fuzz_support.hpp has the helpers);
#   2. fuzz/CMakeLists.txt: dsswarm_fuzz_target(NAME SOURCES NAME.cpp LIBS dsswarm_...);
#   3. scripts/fuzz.sh --make-corpus NAME, and commit fuzz/corpus/NAME and fuzz/dict/NAME.dict.
# The script runs every executable it finds in DIR/fuzz/.
set -uo pipefail
cd "$(dirname "$0")/.."

build=build-fuzz
mode=""
seconds=""
runs=""
jobs=1
jobs_given=""
smoke=""
do_build=1
targets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --smoke) mode=run; seconds=8; smoke=1 ;;
    --time) mode=run; seconds="$2"; shift ;;
    --runs) mode=run; runs="$2"; shift ;;
    --make-corpus) mode=corpus ;;
    --build) build="$2"; shift ;;
    --jobs) jobs="$2"; jobs_given=1; shift ;;
    --no-build) do_build="" ;;
    -h|--help) sed -n '2,/^set -uo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "fuzz.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
    *) targets+=("$1") ;;
  esac
  shift
done
if [ -z "$mode" ]; then
  echo "fuzz.sh: give --smoke, --time SECONDS, --runs N or --make-corpus (see --help)" >&2
  exit 2
fi
[ -n "$smoke" ] && [ -z "$jobs_given" ] && jobs=$(nproc)

if [ -n "$do_build" ]; then
  if [ ! -f "$build/CMakeCache.txt" ]; then
    launcher=()
    command -v ccache >/dev/null && launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
    cmake -S . -B "$build" -G Ninja -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
      -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS=-O1 -DDSSWARM_WERROR=ON -DDSSWARM_FUZZ=ON \
      -DDSSWARM_BUILD_BENCH=OFF "${launcher[@]}" >/dev/null || exit 1
  fi
  cmake --build "$build" -j "$(nproc)" --target fuzz_targets || exit 1
fi
if [ ${#targets[@]} -eq 0 ]; then
  for exe in "$build"/fuzz/*; do [ -f "$exe" ] && [ -x "$exe" ] && targets+=("$(basename "$exe")"); done
fi
if [ ${#targets[@]} -eq 0 ]; then
  echo "fuzz.sh: no fuzz targets in $build/fuzz (configure with -DDSSWARM_FUZZ=ON)" >&2
  exit 1
fi

if [ "$mode" = corpus ]; then
  for t in "${targets[@]}"; do
    rm -rf "fuzz/corpus/$t" && rm -f "fuzz/dict/$t.dict"
    DSSWARM_FUZZ_WRITE_SEEDS="fuzz/corpus/$t" DSSWARM_FUZZ_WRITE_DICT="fuzz/dict/$t.dict" "$build/fuzz/$t" || exit 1
    echo "$t: $(ls "fuzz/corpus/$t" | wc -l) seeds, $(du -sb "fuzz/corpus/$t" | cut -f1) bytes"
  done
  exit 0
fi

export ASAN_OPTIONS=detect_leaks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
logs="$build/fuzz-logs"
mkdir -p "$logs"

# Runs one target; its log ends with libFuzzer's final stats.
run_target() {
  local t=$1 corpus="$build/fuzz-corpus/$1" artifacts="$build/fuzz-artifacts/$1"
  mkdir -p "$corpus" "$artifacts"
  local args=(-timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 -detect_leaks=1 -print_final_stats=1
              -artifact_prefix="$artifacts/")
  [ -f "fuzz/dict/$t.dict" ] && args+=(-dict="fuzz/dict/$t.dict")
  [ -n "$runs" ] && args+=(-runs="$runs")
  [ -n "$seconds" ] && args+=(-max_total_time="$seconds")
  local seeds=()
  [ -d "fuzz/corpus/$t" ] && seeds=("fuzz/corpus/$t")
  touch "$logs/$t.start"
  "$build/fuzz/$t" "${args[@]}" "$corpus" "${seeds[@]}" >"$logs/$t.log" 2>&1
  echo $? >"$logs/$t.rc"
}

for t in "${targets[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n; done
  echo "fuzzing $t ..." >&2
  run_target "$t" &
done
wait

failed=0
printf '%-18s %12s %16s %8s  %s\n' target executions corpus crashes result
for t in "${targets[@]}"; do
  log="$logs/$t.log"
  execs=$(awk '/stat::number_of_executed_units/ {print $2}' "$log" | tail -1)
  corpus=$(grep -o 'corp: [0-9]*/[0-9]*[a-zA-Z]*' "$log" | tail -1 | cut -d' ' -f2)
  crashes=$(find "$build/fuzz-artifacts/$t" -type f -newer "$logs/$t.start" \
              \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' \) | wc -l)
  rc=$(cat "$logs/$t.rc")
  result=ok
  if [ "$rc" != 0 ] || [ "$crashes" != 0 ]; then
    result="FAILED (exit $rc; see $log)"
    failed=1
  fi
  printf '%-18s %12s %16s %8s  %s\n' "$t" "${execs:-?}" "${corpus:-?}" "$crashes" "$result"
done
# A clean CI checkout keeps no artifacts: the report and the input (libFuzzer
# prints small inputs in Base64) go to the output, to reproduce from there.
for t in "${targets[@]}"; do
  [ "$(cat "$logs/$t.rc")" = 0 ] && continue
  echo "--- $t: the end of $logs/$t.log ---"
  grep -v -E '^#[0-9]+[[:space:]]+(NEW|REDUCE|pulse|INITED)' "$logs/$t.log" | tail -60
done
exit $failed
