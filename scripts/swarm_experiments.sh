#!/usr/bin/env bash
# The published multi-robot experiments on real data (issue 5): every
# scenario in scenarios/ (split log = experiment 1, forward + backward =
# experiment 2) with merging and without (--no-merge, the baseline), over a
# few seeds, scored by `dsswarm swarm` itself (evaluation.json).
# Usage: scripts/swarm_experiments.sh OUTDIR [SEEDS...]   (default seeds 1 2 3)
# Runs two at a time; BIN picks the binary (default build/dsswarm). Runs whose
# evaluation.json exists are kept, so an interrupted run resumes.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
bin=${BIN:-$here/build/dsswarm}
out=$1; shift
seeds=("$@"); [ ${#seeds[@]} -gt 0 ] || seeds=(1 2 3)
mkdir -p "$out"
jobs=()
for f in "$here"/scenarios/*.yaml; do
  n=$(basename "$f" .yaml)
  for s in "${seeds[@]}"; do jobs+=("$f $n $s merge" "$f $n $s alone"); done
done
run_one() {
  local f=$1 n=$2 s=$3 mode=$4 dir="$out/$2-seed$3-$4" flag=""
  [ "$mode" = alone ] && flag=--no-merge
  [ -s "$dir/evaluation.json" ] && { echo "$n seed $s $mode: already there"; return; }  # resumable
  "$bin" swarm "$f" --out "$dir" --seed "$s" $flag > "$dir.log" 2>&1 && echo "$n seed $s $mode done" ||
    echo "$n seed $s $mode FAILED (see $dir.log)"
}
export -f run_one; export out bin
printf '%s\n' "${jobs[@]}" | xargs -P 2 -L 1 bash -c 'run_one $0 $1 $2 $3'
python3 - "$out" "${seeds[@]}" <<'PY'
import json, os, statistics, sys, glob
out, seeds = sys.argv[1], sys.argv[2:]
names = sorted({os.path.basename(p).split("-seed")[0] for p in glob.glob(os.path.join(out, "*-seed*-merge"))})
def load(n, s, mode):
    try: return json.load(open(os.path.join(out, f"{n}-seed{s}-{mode}", "evaluation.json")))
    except OSError: return None
print("| scenario | agent | error alone (m) | error merged (m) | ratio | cross-agent error (m) | encounters accepted | encounter error mean / worst (m, deg) |")
print("|---|---|---|---|---|---|---|---|")
for n in names:
    per = {}
    cross, acc, tot, enc = [], 0, 0, []
    for s in seeds:
        m, a = load(n, s, "merge"), load(n, s, "alone")
        if not m or not a: continue
        for am, aa in zip(m["agents"], a["agents"]):
            if am["relations"] and aa["relations"]:
                per.setdefault(am["name"], []).append((aa["relations"]["trans_mean"], am["relations"]["trans_mean"]))
        cm = m["cross"].get("metrics") or {}
        if cm.get("used"): cross.append(cm["trans_mean"])
        acc += m["encounter_summary"]["accepted"]; tot += m["encounter_summary"]["total"]
        enc += [(e["trans_error"], e["rot_error_deg"]) for e in m["encounters"] if e["accepted"] and e.get("trans_error") is not None]
    first = True
    for agent, v in per.items():
        alone = statistics.median([x[0] for x in v]); merged = statistics.median([x[1] for x in v])
        row = [n if first else "", agent, f"{alone:.3f}", f"{merged:.3f}", f"{merged/alone:.2f}"]
        if first:
            row += [f"{statistics.median(cross):.3f}" if cross else "–", f"{acc}/{tot}",
                    (f"{statistics.mean(e[0] for e in enc):.3f} / {max(e[0] for e in enc):.3f} m, "
                     f"{statistics.mean(e[1] for e in enc):.2f} / {max(e[1] for e in enc):.2f}°") if enc else "–"]
        else:
            row += ["", "", ""]
        print("| " + " | ".join(row) + " |")
        first = False
print(f"\n(medians over seeds {' '.join(seeds)}; per-agent error = relation metric trans mean on the agent's own trajectory)")
PY
