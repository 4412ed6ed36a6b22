#!/usr/bin/env bash
# Runs the simulated swarm (`dsswarm demo`) over many seeds and summarizes
# what issue 5 asks to show: every accepted encounter's transform error, the
# wrong merges, each robot's map coverage and ATE, time and memory.
# Usage: scripts/swarm_sim_eval.sh OUTDIR FIRST_SEED LAST_SEED [-- extra demo flags]
# Runs two seeds at a time; BIN picks the binary (default build/dsswarm).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
bin=${BIN:-$here/build/dsswarm}
out=$1 first=$2 last=$3; shift 3
[ "${1:-}" = "--" ] && shift
mkdir -p "$out"
export bin out EXTRA="$*"
run_one() {
  local s=$1 dir="$out/seed$1"
  # shellcheck disable=SC2086 # EXTRA is a list of flags
  if /usr/bin/time -f "%M" -o "$dir.rss" "$bin" demo --run-seed "$s" --out "$dir" $EXTRA > "$dir.log" 2>&1; then
    echo "seed $s done"
  else
    echo "seed $s FAILED (see $dir.log)"
  fi
}
export -f run_one
seq "$first" "$last" | xargs -P 2 -I{} bash -c 'run_one {}'
python3 - "$out" "$first" "$last" <<'PY'
import json, os, statistics, sys
out, first, last = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
acc = tot = wrong = wrong_local = wrong_aligned = 0
errs = {"error": [], "causal_error": [], "aligned_error": [], "frame_error": []}
cover, ate, match_ms, merge_ms, nbytes, rss, failed = [], [], [], [], [], [], []
for s in range(first, last + 1):
    d = os.path.join(out, f"seed{s}")
    try:
        st = json.load(open(os.path.join(d, "stats.json")))
        enc = json.load(open(os.path.join(d, "encounters.json")))["encounters"]
    except OSError:
        failed.append(s); continue
    for e in enc:
        tot += 1
        match_ms.append(e["match_ms"]); nbytes.append(e["bytes"])
        if not e["accepted"]: continue
        acc += 1; merge_ms.append(e["merge_ms"])
        for k in errs:
            if k in e: errs[k].append((e[k][0], e[k][1], s, e["time"]))
        off = lambda k: e[k][0] > 0.3 or e[k][1] > 3.0
        if off("error") and off("aligned_error"): wrong += 1
        wrong_local += off("error"); wrong_aligned += off("aligned_error")
    for a in st["agents"]:
        cover.append((a["coverage"], s, a["name"])); ate.append(a["ate_rmse"])
    rss.append(int(open(os.path.join(out, f"seed{s}.rss")).read().split()[-1]) / 1024)
def pct(v, p): v = sorted(v); return v[min(len(v) - 1, int(p * len(v)))]
print(f"seeds {first}..{last}: {len(failed)} failed {failed}")
print(f"encounters {tot}, accepted {acc} ({100*acc/max(1,tot):.0f}%); off by > 0.3 m or 3 deg: {wrong_local} against the true relative pose, "
      f"{wrong_aligned} against the aligned frames, {wrong} against both (wrong merges)")
for k, v in errs.items():
    if not v: continue
    xy = [x[0] for x in v]; th = [x[1] for x in v]
    worst = max(v, key=lambda x: x[0])
    print(f"  {k:14s} median {statistics.median(xy):.3f} m / {statistics.median(th):.2f} deg, 95% {pct(xy,.95):.3f} m / {pct(th,.95):.2f} deg, "
          f"max {max(xy):.3f} m (seed {worst[2]} t={worst[3]:.0f}) / {max(th):.2f} deg, "
          f"within 0.05 m & 0.5 deg: {sum(1 for x in v if x[0] <= 0.05 and x[1] <= 0.5)}/{len(v)} "
          f"(outside by the angle only {sum(1 for x in v if x[0] <= 0.05 and x[1] > 0.5)}, "
          f"the distance only {sum(1 for x in v if x[0] > 0.05 and x[1] <= 0.5)}, "
          f"both {sum(1 for x in v if x[0] > 0.05 and x[1] > 0.5)})")
if cover:
    worst = min(cover)
    print(f"coverage: min {worst[0]*100:.1f}% (seed {worst[1]} {worst[2]}), median {100*statistics.median([c[0] for c in cover]):.1f}%, "
          f"robots >= 90%: {sum(1 for c in cover if c[0] >= 0.9)}/{len(cover)}")
    print(f"ATE RMSE per robot: median {statistics.median(ate):.3f} m, 95% {pct(ate,.95):.3f} m, max {max(ate):.3f} m")
if match_ms:
    print(f"per encounter: match median {statistics.median(match_ms):.0f} ms, merge median {statistics.median(merge_ms) if merge_ms else 0:.0f} ms, "
          f"exchange median {statistics.median(nbytes)/1000:.0f} kB; peak RSS per run median {statistics.median(rss):.0f} MB")
PY
