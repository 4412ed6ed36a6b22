#!/usr/bin/env bash
# Runs `dsswarm run` on the real logs over several seeds and scores each run
# with the relation metric. Usage: scripts/eval_datasets.sh OUTDIR [SEEDS...] [-- extra run flags]
# Prints one line per run and a summary per dataset; runs two at a time.
# BIN picks the dsswarm binary (default build/dsswarm).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
data=${DSSWARM_DATA:-$here/../shared/data}
bin=${BIN:-$here/build/dsswarm}
out=$1; shift
seeds=(); extra=()
while [ $# -gt 0 ]; do
  if [ "$1" = "--" ]; then shift; extra=("$@"); break; fi
  seeds+=("$1"); shift
done
[ ${#seeds[@]} -gt 0 ] || seeds=(1 2 3 4 5)
datasets=${DATASETS:-"mit-csail fr079 intel"}
mkdir -p "$out"
jobs=()
for d in $datasets; do
  for s in "${seeds[@]}"; do
    jobs+=("$d $s")
  done
done
run_one() {
  local d=$1 s=$2 dir="$out/$1-seed$2"
  # shellcheck disable=SC2086 # EXTRA is a list of flags
  "$bin" run "$data/carmen/$d.log.gz" --out "$dir" --seed "$s" $EXTRA > "$dir.log" 2>&1 || { echo "$d seed $s: run failed (see $dir.log)"; return; }
  local m; m=$("$bin" eval relations "$dir/trajectory.tum" "$data/relations/$d.relations" | tail -n 1)
  local sps; sps=$(python3 -c "import json;print(round(json.load(open('$dir/stats.json'))['scans_per_second']))")
  echo "$d seed $s $m scans_per_second=$sps" | tee "$dir.metrics"
}
EXTRA="${extra[*]}"
export -f run_one; export out data bin EXTRA
printf '%s\n' "${jobs[@]}" | xargs -P 2 -L 1 bash -c 'run_one $0 $1' > /dev/null
python3 - "$out" $datasets <<'PY'
import json, statistics, sys, glob, os
out = sys.argv[1]
for d in sys.argv[2:]:
    rows = []
    for f in sorted(glob.glob(os.path.join(out, f"{d}-seed*.metrics"))):
        line = open(f).read().split()
        j = json.loads(" ".join(line[3:-1]))
        rows.append((int(line[2]), j["trans_mean"], j["rot_mean_deg"], int(line[-1].split("=")[1])))
    if not rows: continue
    t = [r[1] for r in rows]
    print(f"{d:10s} trans_mean median {statistics.median(t):.3f} m, worst {max(t):.3f} m, rot median {statistics.median([r[2] for r in rows]):.2f} deg, "
          f"scans/s median {statistics.median([r[3] for r in rows])}  | per seed: " + ", ".join(f"{r[0]}:{r[1]:.3f}" for r in rows))
PY
