#!/usr/bin/env bash
# dsswarm beside the peers a user would pick from Debian instead — MRPT's
# icp-slam and rbpf-slam — on the shared logs intel, fr079 and mit-csail
# (../shared/data), one run after another in one invocation. Per system and
# dataset: wall and CPU seconds of the whole process (reading the log, SLAM,
# writing the trajectory), scans/s (scans in the log / wall seconds, and per
# CPU second, the steadier figure on a shared machine), peak RSS (GNU time),
# and the relation error scored by `dsswarm eval relations --max-dt 0.001`
# (every pose within 1 ms of its relation's times, else it counts as missing).
# Writes bench/results/compare.md, compare.json and compare.png (a gnuplot
# chart; gnuplot is a measurement tool here, not a dependency of dsswarm).
#
# Usage: bench/compare.sh [--only NAMES] [--skip NAMES] [--callgrind | --callgrind-only] [--out DIR]
#   NAMES        comma-separated systems (dsswarm, dsswarm-filter, icp-slam,
#                rbpf-slam) and datasets (mit-csail, fr079, intel). --only keeps
#                the named ones (every system if it names none, likewise
#                datasets); --skip drops them. Default: everything (rbpf-slam
#                on intel alone takes many minutes).
#   --callgrind  also count instructions: callgrind on the first 300 scans of
#                mit-csail (`dsswarm run --max-scans 300 --no-images`), SLAM
#                only (Slam::process and Slam::finish) and the whole process; instructions per
#                scan, the top functions and a Raspberry Pi estimate go into
#                compare.md/json. --callgrind-only: that alone, into
#                callgrind.md/json (compare.md/json are left as they are).
#   --out DIR    where the results go (default bench/results); work files
#                (rawlogs, run outputs, logs) go to build/compare/.
#
# The MRPT runs use Debian's sample configurations (mrpt-common) with only the
# output settings changed (no GUI window, no 3D scenes or map images, no
# debug logging) and rbpf-slam's random seed fixed; the logs are converted
# with bench/tools/carmen2rawlog, which keeps the scans' timestamps (see its
# header). Method and caveats: docs/performance.md.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
data=${DSSWARM_DATA:-$here/../shared/data}
out=$here/bench/results
work=$here/build/compare
only="" skip="" callgrind=0 compare=1
while [ $# -gt 0 ]; do
  case $1 in
    --only) only=$2; shift 2 ;;
    --skip) skip=$2; shift 2 ;;
    --callgrind) callgrind=1; shift ;;
    --callgrind-only) callgrind=1; compare=0; shift ;;
    --out) out=$(realpath -m "$2"); shift 2 ;;
    -h|--help) sed -n '2,/^set -e/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) echo "error: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
all_systems=(dsswarm dsswarm-filter icp-slam rbpf-slam)
all_datasets=(mit-csail fr079 intel)
for name in ${only//,/ } ${skip//,/ }; do
  [[ " ${all_systems[*]} ${all_datasets[*]} " == *" $name "* ]] || { echo "error: unknown name '$name'" >&2; exit 2; }
done
# The named ones of `kind` (all of them if --only names none), less --skip's.
select_names() {
  local -a kind=("$@") picked=()
  local n
  for n in "${kind[@]}"; do [[ ",$only," == *",$n,"* ]] && picked+=("$n"); done
  [ ${#picked[@]} -gt 0 ] || picked=("${kind[@]}")
  for n in "${picked[@]}"; do [[ ",$skip," == *",$n,"* ]] || echo "$n"; done
}
mapfile -t systems < <(select_names "${all_systems[@]}")
mapfile -t datasets < <(select_names "${all_datasets[@]}")
for d in "${datasets[@]}"; do
  [ -f "$data/carmen/$d.log.gz" ] || { echo "error: $data/carmen/$d.log.gz not found (set DSSWARM_DATA)" >&2; exit 1; }
done

# Measurement tools: MRPT apps and sample configs, libmrpt for the converter,
# gnuplot for the chart, valgrind, GNU time, python3 for the report.
"$here/scripts/install_deps.sh" mrpt-apps mrpt-common libmrpt-dev gnuplot-nox valgrind time python3
cmake -S "$here" -B "$here/build" -G Ninja -DCMAKE_BUILD_TYPE=Release > /dev/null
[ "$(sed -n 's/^CMAKE_BUILD_TYPE:[A-Z]*=//p' "$here/build/CMakeCache.txt")" = Release ] ||
  { echo "error: build/ is not a Release build" >&2; exit 1; }
cmake --build "$here/build" --target dsswarm > /dev/null
dsswarm=$here/build/dsswarm
tools=$here/bench/compare_tools.py
mkdir -p "$work/runs" "$work/out"
rm -f "$work"/runs/*.json "$work/callgrind.json"

# --- one run -------------------------------------------------------------
# run_timed NAME CMD...: runs CMD under GNU time, its output in the work folder.
run_timed() {
  local name=$1; shift
  local rc=0
  /usr/bin/time -f "%e %U %S %M" -o "$work/out/$name.time" "$@" > "$work/out/$name.log" 2>&1 || rc=$?
  return $rc
}
# record SYSTEM DATASET TRAJECTORY [ERROR]: scores the trajectory, writes runs/SYSTEM-DATASET.json.
record() {
  local system=$1 dataset=$2 tum=$3 error=${4:-} rel=null
  if [ -z "$error" ]; then
    rel=$("$dsswarm" eval relations "$tum" "$data/relations/$dataset.relations" --max-dt 0.001 | tail -n 1) ||
      { rel=null; error="eval relations failed"; }
  fi
  python3 "$tools" record "$work/runs/$system-$dataset.json" "$system" "$dataset" "$work/$dataset.stamps" \
    "$work/out/$system-$dataset.time" "$rel" "$error"
}

# MRPT's sample configuration with output settings replaced: ini KEY=VALUE...
mrpt_config() {
  local sample=$1 target=$2; shift 2
  cp "$sample" "$target"
  local kv key
  for kv in "$@"; do
    key=${kv%%=*}
    if grep -qE "^\s*$key\s*=" "$target"; then
      sed -i -E "s|^\s*$key\s*=.*|$kv|" "$target"
    else
      sed -i -E "0,/^\[MappingApplication\]/s||[MappingApplication]\n$kv|" "$target"
    fi
  done
}
icp_sample=/usr/share/mrpt/config_files/icp-slam/icp-slam_demo_classic.ini
rbpf_sample=/usr/share/mrpt/config_files/rbpf-slam/gridmapping_RBPF_ICPbased_intel.ini

run_dsswarm() {  # SYSTEM DATASET [flags]
  local system=$1 dataset=$2; shift 2
  local dir=$work/out/$system-$dataset error=""
  run_timed "$system-$dataset" "$dsswarm" run "$data/carmen/$dataset.log.gz" --out "$dir" --no-images "$@" ||
    error="dsswarm run failed (see $work/out/$system-$dataset.log)"
  record "$system" "$dataset" "$dir/trajectory.tum" "$error"
}

run_mrpt() {  # SYSTEM DATASET
  local system=$1 dataset=$2
  local name=$system-$dataset dir=$work/out/$1-$2 ini=$work/out/$1-$2.ini error=""
  if [ "$system" = icp-slam ]; then
    mrpt_config "$icp_sample" "$ini" SHOW_PROGRESS_3D_REAL_TIME=0 SAVE_3D_SCENE=0 LOG_FREQUENCY=1000000 \
      "logOutput_dir=$dir"
  else
    mrpt_config "$rbpf_sample" "$ini" SHOW_PROGRESS_IN_WINDOW=0 SAVE_3D_SCENE=0 SAVE_MAP_IMAGES=0 \
      LOG_FREQUENCY=1000000 "verbosity_level=INFO" RANDOM_SEED=1 "logOutput_dir=$dir"
  fi
  run_timed "$name" "$system" "$ini" "$work/$dataset.rawlog" < /dev/null || error="$system failed (see $work/out/$name.log)"
  [ -n "$error" ] || python3 "$tools" mrpt-tum "$dir/log_estimated_path.txt" "$work/$dataset.stamps" \
    "$dir/trajectory.tum" || error="no usable path in $dir/log_estimated_path.txt"
  record "$system" "$dataset" "$dir/trajectory.tum" "$error"
}

# --- the comparison --------------------------------------------------------
load() { cut -d' ' -f1-3 /proc/loadavg; }
load_start=$(load)
if [ $compare -eq 1 ]; then
  if [[ " ${systems[*]} " == *" icp-slam "* || " ${systems[*]} " == *" rbpf-slam "* ]]; then
    cmake -S "$here/bench/tools/carmen2rawlog" -B "$here/build/carmen2rawlog" -G Ninja > /dev/null
    cmake --build "$here/build/carmen2rawlog" > /dev/null
  fi
  for dataset in "${datasets[@]}"; do
    if [ -x "$here/build/carmen2rawlog/carmen2rawlog" ]; then
      "$here/build/carmen2rawlog/carmen2rawlog" "$data/carmen/$dataset.log.gz" "$work/$dataset" 2> /dev/null
    else  # dsswarm only: the scan count and timestamps from its own reader
      zcat "$data/carmen/$dataset.log.gz" | awk '$1 == "FLASER" { print $(NF-2) }' > "$work/$dataset.stamps"
    fi
    for system in "${systems[@]}"; do
      case $system in
        dsswarm) run_dsswarm dsswarm "$dataset" ;;
        dsswarm-filter) run_dsswarm dsswarm-filter "$dataset" --filter ;;
        *) run_mrpt "$system" "$dataset" ;;
      esac
    done
  done
fi

# --- instruction counts ------------------------------------------------------
if [ $callgrind -eq 1 ]; then
  cg_log=mit-csail cg_scans=300
  for part in slam whole; do
    toggle=()
    # SLAM: every scan's processing and the end of the run (run_slam reaches
    # them through a tail call, which callgrind does not count as inside it).
    [ $part = slam ] && toggle=("--toggle-collect=dsswarm::Slam::process(*" "--toggle-collect=dsswarm::Slam::finish(*")
    valgrind --tool=callgrind "${toggle[@]}" --callgrind-out-file="$work/callgrind.$part.out" \
      "$dsswarm" run "$data/carmen/$cg_log.log.gz" --out "$work/out/callgrind-$part" --max-scans $cg_scans \
      --no-images > "$work/out/callgrind-$part.log" 2>&1
    callgrind_annotate "$work/callgrind.$part.out" > "$work/callgrind.$part.txt"
  done
  python3 "$tools" callgrind "$work/callgrind.slam.txt" "$work/callgrind.whole.txt" "$work/callgrind.json" \
    --scans $cg_scans --log $cg_log
fi

# --- the report -------------------------------------------------------------
commit=$(git -C "$here" rev-parse --short HEAD)
git -C "$here" diff --quiet HEAD -- src bench || commit="$commit (with uncommitted changes)"
python3 - "$work/meta.json" "$commit" "$load_start" "$(load)" "$icp_sample" "$rbpf_sample" <<'PY'
import json, os, subprocess, sys, datetime
path, commit, load_start, load_end, icp, rbpf = sys.argv[1:]
cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "unknown CPU")
mrpt = subprocess.run(["dpkg-query", "-W", "-f=${Version}", "mrpt-apps"], capture_output=True, text=True).stdout
json.dump({"date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"), "commit": commit,
           "cpu": cpu, "cores": os.cpu_count(), "load_start": load_start, "load_end": load_end, "mrpt": mrpt,
           "configs": {"dsswarm": "defaults, seed 1, `--no-images`", "dsswarm-filter": "the same with `--filter`",
                       "icp-slam": f"`{os.path.basename(icp)}` (MRPT {mrpt})",
                       "rbpf-slam": f"`{os.path.basename(rbpf)}` (MRPT {mrpt}), RANDOM_SEED=1"}},
          open(path, "w"), indent=2)
PY
python3 "$tools" report "$work" "$out"
if ls "$work"/runs/*.json > /dev/null 2>&1; then
  columns=$(cat "$work/chart_columns")
  gnuplot <<GP
set terminal pngcairo size 1400,950 font "DejaVu Sans,11"
set output "$out/compare.png"
set multiplot layout 2,2 title "dsswarm and MRPT on the shared logs (bench/compare.sh, $(date -u +%F))"
set style data histogram
set style histogram clustered gap 1
set style fill solid 0.85 border -1
set boxwidth 0.9
set key top left font ",9"
set grid ytics
set logscale y
set title "scans per second (log scale; higher is better)"
plot for [i=2:$((columns + 1))] "$work/chart_scans_per_second.dat" using i:xtic(1) title columnheader(i)
set title "scans per CPU second (log scale; higher is better)"
plot for [i=2:$((columns + 1))] "$work/chart_scans_per_cpu_second.dat" using i:xtic(1) title columnheader(i)
set title "relation error, mean translation in m (log scale; lower is better)"
plot for [i=2:$((columns + 1))] "$work/chart_trans_error.dat" using i:xtic(1) title columnheader(i)
unset logscale y
set yrange [0:*]
set title "peak RSS in MB (lower is better)"
plot for [i=2:$((columns + 1))] "$work/chart_peak_rss_mb.dat" using i:xtic(1) title columnheader(i)
unset multiplot
GP
fi
if [ $compare -eq 1 ]; then
  echo "results: $out/compare.md, compare.json, compare.png"
else
  echo "results: $out/callgrind.md, callgrind.json"
fi
