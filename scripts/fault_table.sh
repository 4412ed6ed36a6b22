#!/usr/bin/env bash
# The fault table (docs/faults.md): a 3-robot --sim swarm of `dsswarm agent`
# processes on this machine, run once per fault, each fault injected while
# the robots map and meet; then, per run, what happened and whether anything
# was lost, from the robots' own outputs (stats.json, encounters.json,
# checkpoints).
set -euo pipefail

usage() {
  cat <<'EOF'
usage: scripts/fault_table.sh [--build DIR] [--out DIR] [--doc FILE] [--rate X] [--only CASE...]

Runs a 3-robot simulated swarm (`dsswarm agent --sim 1`, robots 1-3, real time
x RATE) once per fault and writes a Markdown table to --doc:

  baseline        no fault
  kill            kill -9 robot1 mid-run, not restarted
  resume          kill -9 robot1, restarted with --resume (its checkpoint)
  restart         kill -9 robot1, restarted without --resume (from nothing;
                  its earlier checkpoint is set aside in robot1/previous/)
  loss10, loss30  every robot drops 10% / 30% of the UDP packets it sends
  partition       robot1 cut off from the others for 12 s, then back
  malformed       a test publisher sends 4 rounds of malformed, truncated,
                  oversized, wrong-version, non-finite, corrupt, misdirected
                  and replayed messages into robot1's inbox
  unauthorized    secured swarm (dsswarm keys); robot3's certificate is from
                  another CA

Loss and partition run each robot in its own network namespace, joined by a
bridge, loss and cuts done with nftables (tc netem is not available here):
they need root, `ip` and `nft`, and are reported as skipped otherwise.

Options:
  --build DIR   build folder with dsswarm and multiprocess_inject (default build)
  --out DIR     run folders, kept for inspection (default out/faults)
  --doc FILE    the table (default docs/faults.md)
  --rate X      playback speed (default 8)
  --only CASE   run only these cases (repeatable); the table then has only them
  --table-only  do not run anything: write the table from the runs in --out
  -h, --help    this text
EOF
}

cd "$(dirname "$0")/.."
build=build out=out/faults doc=docs/faults.md rate=8 only=() table_only=0
while [ $# -gt 0 ]; do
  case "$1" in
    --build) build=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --doc) doc=$2; shift 2 ;;
    --rate) rate=$2; shift 2 ;;
    --only) only+=("$2"); shift 2 ;;
    --table-only) table_only=1; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "error: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
done
dsswarm=$(realpath "$build/dsswarm")
inject=$(realpath "$build/multiprocess_inject")
for b in "$dsswarm" "$inject"; do
  [ -x "$b" ] || { echo "error: $b missing: cmake --build $build --target dsswarm multiprocess_inject" >&2; exit 1; }
done
mkdir -p "$out"
out=$(realpath "$out")
[ "$table_only" = 1 ] || rm -f "$out/load"
cases=(baseline kill resume restart loss10 loss30 partition malformed unauthorized)
[ ${#only[@]} -gt 0 ] && cases=("${only[@]}")

tag=$$
domain=$((150 + tag % 60))
pids=()
namespaces=()

cleanup() {
  for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done
  for ns in "${namespaces[@]}"; do ip netns del "$ns" 2>/dev/null || true; done
  pids=() namespaces=()
}
trap cleanup EXIT

can_netns() { [ "$(id -u)" -eq 0 ] && command -v ip >/dev/null && command -v nft >/dev/null; }

# Robot k in namespace dsf-r<k>-<tag>, interface dsv<k>-<tag>, all on a bridge in dsf-hub-<tag>.
netns_up() {
  local hub=dsf-hub-$tag
  ip netns add "$hub"; namespaces+=("$hub")
  ip -n "$hub" link add br0 type bridge mcast_snooping 0
  ip -n "$hub" link set br0 up
  for k in 1 2 3; do
    local ns=dsf-r$k-$tag
    ip netns add "$ns"; namespaces+=("$ns")
    ip link add "dsv$k-$tag" netns "$ns" type veth peer name "dsh$k-$tag" netns "$hub"
    ip -n "$hub" link set "dsh$k-$tag" master br0 up
    ip -n "$ns" addr add "10.215.$((tag % 250)).$k/24" dev "dsv$k-$tag"
    ip -n "$ns" link set lo up
    ip -n "$ns" link set "dsv$k-$tag" up
  done
}

loss() {  # percent: every robot drops that share of the UDP packets it sends
  for k in 1 2 3; do
    ip netns exec "dsf-r$k-$tag" nft "table inet loss { chain out { type filter hook output priority 0; \
      oifname \"dsv$k-$tag\" meta l4proto udp counter; \
      oifname \"dsv$k-$tag\" meta l4proto udp numgen random mod 100 < $1 counter drop; }; }"
  done
}

loss_counts() {  # "dropped of sent" over the three robots
  local sent=0 dropped=0
  for k in 1 2 3; do
    read -r s d < <(ip netns exec "dsf-r$k-$tag" nft list table inet loss | grep -o 'packets [0-9]*' | awk '{print $2}' | xargs)
    sent=$((sent + s)) dropped=$((dropped + d))
  done
  echo "$dropped of $sent"
}

cut_off() {  # robot $1 neither sends nor receives
  ip netns exec "dsf-r$1-$tag" nft "table inet cut { chain out { type filter hook output priority 0; \
    oifname \"dsv$1-$tag\" drop; }; chain in { type filter hook input priority 0; iifname \"dsv$1-$tag\" drop; }; }"
}
heal() { ip netns exec "dsf-r$1-$tag" nft delete table inet cut; }

# start_agent DIR K [extra agent options...]: robot K of the run in DIR, in the
# background, its log in DIR/robotK.log (appended: a restart adds to it).
start_agent() {
  local dir=$1 k=$2; shift 2
  local prefix=() net=(--interface lo)
  if [ "$use_netns" = 1 ]; then
    prefix=(ip netns exec "dsf-r$k-$tag")
    net=(--interface "dsv$k-$tag")
  fi
  local swarm=(--swarm-domain "$domain" --swarm "faults$tag")
  [ -n "$keys_for" ] && swarm=(--keys "$($keys_for "$k")")
  "${prefix[@]}" "$dsswarm" agent --name "robot$k" --out "$dir/robot$k" --sim 1 --robot "$k" --robots 3 \
    --rate "$rate" --start-at "$start_at" "${net[@]}" "${swarm[@]}" --no-ros-output \
    --config "$dir/config.json" --checkpoint-period 1 --linger 5 "$@" >>"$dir/robot$k.log" 2>&1 &
  pid[$k]=$!
  pids+=($!)
}

at() {  # sleeps until $1 seconds of wall time after the robots' clock 0
  local wait
  wait=$(python3 -c "import time; print(max(0.0, $start_at + $1 - time.time()))")
  sleep "$wait"
}

unauthorized_keys() { [ "$1" = 3 ] && echo "$run/other_ca" || echo "$run/keys"; }

run_case() {
  local name=$1
  run=$out/$name
  rm -rf "$run"; mkdir -p "$run"
  echo '{"swarm": {"exchange_timeout": 30}}' >"$run/config.json"
  cut -d' ' -f1 /proc/loadavg >>"$out/load"
  use_netns=0 keys_for="" note=""
  case "$name" in
    loss10|loss30|partition)
      if ! can_netns; then echo "skipped (needs root, ip, nft)" >"$run/skipped"; return; fi
      use_netns=1; netns_up ;;
    unauthorized)
      "$dsswarm" keys init "$run/keys" --swarm "$domain" >/dev/null
      "$dsswarm" keys init "$run/other_ca" --swarm "$domain" >/dev/null
      for k in 1 2; do "$dsswarm" keys add "$run/keys" "robot$k" >/dev/null; done
      "$dsswarm" keys add "$run/other_ca" robot3 >/dev/null
      keys_for=unauthorized_keys ;;
  esac
  [ "$name" = loss10 ] && loss 10
  [ "$name" = loss30 ] && loss 30
  start_at=$(python3 -c "import time; print(f'{time.time() + 4:.3f}')")
  declare -A pid
  for k in 1 2 3; do start_agent "$run" "$k"; done
  case "$name" in
    kill|resume|restart)
      at 9; kill -9 "${pid[1]}"; wait "${pid[1]}" 2>/dev/null || true
      note="killed at t=9 s"
      if [ "$name" != kill ]; then
        sleep 2
        if [ "$name" = resume ]; then start_agent "$run" 1 --resume; else start_agent "$run" 1; fi
      fi ;;
    partition)
      at 7; cut_off 1; at 19; heal 1; note="cut off t=7..19 s" ;;
    malformed)
      note=$("$inject" "$domain" "faults$tag" robot1 4 3) ;;
  esac
  for k in 1 2 3; do
    [ "$name" = kill ] && [ "$k" = 1 ] && continue
    wait "${pid[$k]}" || echo "warning: $name: robot$k exited with $?" >&2
  done
  [ "$name" = kill ] && [ -n "${pid[1]:-}" ] || true
  case "$name" in loss10|loss30) note="$(loss_counts) UDP packets dropped" ;; esac
  echo "$note" >"$run/note"
  cleanup
}

for c in "${cases[@]}"; do
  [ "$table_only" = 1 ] && break
  echo "fault_table: $c ..." >&2
  t0=$SECONDS
  run_case "$c"
  echo "fault_table: $c done in $((SECONDS - t0)) s" >&2
done

python3 - "$out" "$doc" "$rate" "${cases[@]}" <<'EOF'
import json, os, sys
out, doc, rate, cases = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
robots = ["robot1", "robot2", "robot3"]
files = ["trajectory.tum", "map.yaml", "merged_map.yaml", "encounters.json", "stats.json", "checkpoint.dsmap", "checkpoint.json"]

def load(path):
    with open(path) as f:
        return json.load(f)

def poses(path):
    with open(path) as f:
        t = [float(l.split()[0]) for l in f if l.strip() and not l.startswith("#")]
    return t, all(b > a for a, b in zip(t, t[1:]))

def robot_figures(run, r):
    d = os.path.join(run, r)
    if not os.path.exists(os.path.join(d, "stats.json")):  # killed, not restarted: what its checkpoint kept
        c = load(os.path.join(d, "checkpoint.json"))
        t, ordered = poses(os.path.join(d, "trajectory.tum"))
        ok = os.path.exists(os.path.join(d, "checkpoint.dsmap")) and ordered and len(t) == c["scans_processed"]
        return {"killed": True, "processed": c["scans_processed"], "complete": ok}
    s = load(os.path.join(d, "stats.json"))
    enc = load(os.path.join(d, "encounters.json"))["encounters"]
    t, ordered = poses(os.path.join(d, "trajectory.tum"))
    ok = all(os.path.exists(os.path.join(d, f)) for f in files) and ordered and len(t) == s["scans_processed"]
    return {"killed": False, "accepted": s["encounters_accepted"], "knows": sorted(l["origin"] for l in s["knows"]),
            "processed": s["scans_processed"], "skipped": s["scans_skipped"], "complete": ok,
            "rejected": s["messages_rejected"], "abandoned": sum(o["end"] == "abandoned" for o in enc),
            "in_checkpoint": s.get("scans_in_checkpoint", 0), "enc": enc}

def short(r): return r.replace("robot", "r")

def happened(case, figs, note):
    f1 = figs["robot1"]
    again = sum(o["end"] == "accepted" for o in f1.get("enc", []))  # robot1's outputs: its last run
    peers_of_1 = [o for r in ("robot2", "robot3") for o in figs[r].get("enc", []) if o["peer"] == "robot1"]
    ab1 = [o for o in peers_of_1 if o["end"] == "abandoned"]
    reasons = sorted({o["reason"].split(" (")[0] for o in ab1})
    if case == "baseline": return "nothing injected"
    if case == "kill": return f"robot1 {note}; r2, r3 abandoned {len(ab1)} encounters with it ({'; '.join(reasons[:2]) or 'none open'}) and went on"
    if case == "resume":
        return (f"robot1 {note}, restarted with --resume 2 s later: went on from its checkpoint "
                f"(the replayed run's scans of the outage arrive at once, overdue: skipped); peers abandoned {len(ab1)} open encounters; "
                f"after the restart robot1 accepted {again} encounters")
    if case == "restart":
        kept = load(os.path.join(out, case, "robot1", "previous", "checkpoint.json"))["scans_processed"]
        return (f"robot1 {note}, restarted without --resume: a new map from nothing, its earlier checkpoint "
                f"({kept} scans) set aside in robot1/previous/; peers abandoned {len(ab1)} encounters; "
                f"after the restart robot1 accepted {again}")
    if case.startswith("loss"): return f"{note}; Cyclone's reliable retransmits repair the exchange"
    if case == "partition":
        healed = (4 + 19) * float(rate)  # the heal on the robots' swarm clock (s since start x rate), roughly
        after = sum(o["end"] == "accepted" and o["started"] > healed for o in f1["enc"])
        return (f"robot1 {note}; peers abandoned {len(ab1)} encounters with it ({'; '.join(reasons[:2])}); "
                f"after the heal robot1 accepted {after} encounters")
    if case == "malformed": return f"injected into robot1 ({note}); all refused and counted: robot1 messages_rejected {json.dumps(f1['rejected'])}"
    if case == "unauthorized":
        tried = [o for r in ("robot1", "robot2") for o in figs[r]["enc"] if o["peer"] == "robot3"]
        heard = sum(o["bytes_received"] for o in tried)
        return f"robot3 (another CA) never matched: r1, r2 opened {len(tried)} encounters with it, received {heard} bytes from it"
    return note

def lost(case, figs):
    problems = [f"{r} outputs incomplete" for r in robots if not figs[r]["complete"]]
    if case == "unauthorized":
        for r in ("robot1", "robot2"):
            if "robot3" in figs[r]["knows"]: problems.append(f"{r} holds robot3's map")
        if "robot1" not in figs["robot2"]["knows"]: problems.append("r1, r2 did not merge")
    if case == "restart" and not os.path.exists(os.path.join(out, case, "robot1", "previous", "checkpoint.dsmap")):
        problems.append("robot1's earlier checkpoint overwritten")
    if case == "malformed":
        sent = {k: int(v) for k, v in (p.split(": ") for p in open(os.path.join(out, case, "note")).read().strip().split(", "))}
        if sent != figs["robot1"]["rejected"]: problems.append(f"robot1 counted {figs['robot1']['rejected']}, sent {sent}")
    return "nothing lost" if not problems else "LOST: " + "; ".join(problems)

rows = []
for case in cases:
    run = os.path.join(out, case)
    if os.path.exists(os.path.join(run, "skipped")):
        rows.append(f"| {case} | {open(os.path.join(run, 'skipped')).read().strip()} | – | – | – | – | – |")
        continue
    note = open(os.path.join(run, "note")).read().strip()
    figs = {r: robot_figures(run, r) for r in robots}
    acc = " / ".join("killed" if figs[r]["killed"] else str(figs[r]["accepted"]) for r in robots)
    knows = " / ".join("–" if figs[r]["killed"] else (",".join(short(o) for o in figs[r]["knows"]) or "none") for r in robots)
    scans = " / ".join(f"{figs[r]['processed']}" + ("" if figs[r]["killed"] else f"/{figs[r]['skipped']}") for r in robots)
    complete = " / ".join(("checkpoint" if figs[r]["killed"] else "yes") if figs[r]["complete"] else "NO" for r in robots)
    rows.append(f"| {case} | {happened(case, figs, note)} | {lost(case, figs)} | {acc} | {knows} | {scans} | {complete} |")

loads = [float(x) for x in open(os.path.join(out, "load")).read().split()]
load = f"{min(loads):.1f}-{max(loads):.1f}"
with open(doc, "w") as f:
    f.write(f"""# Fault table

What a swarm of robot processes does when things go wrong, measured by
`scripts/fault_table.sh` (see its `--help`): three `dsswarm agent --sim 1`
processes (robots 1-3 of the simulated swarm, {rate}x real time, exchange
time-out 30 s, checkpoints every second), each fault injected while they map
and meet, on this 2-core machine shared with other work (load average
{load} at the starts of the runs: scans are skipped when a robot falls behind). Figures per robot, r1 / r2 / r3, from their own outputs:
encounters accepted (stats.json), the map layers each holds of the others,
scans processed/skipped, and whether its outputs are complete (every output
file readable, one pose per processed scan in time order; for a robot killed
and not restarted: its last checkpoint, map and poses, intact).

| fault | what happened | nothing lost | encounters accepted | layers known | scans processed/skipped | outputs complete |
|---|---|---|---|---|---|---|
""")
    f.write("\n".join(rows) + "\n")
    f.write("""
Loss and partition run each robot in its own network namespace on a bridge,
nftables dropping the share of UDP packets each robot sends (tc netem is not
available on this machine), or every packet of the cut-off robot. The same
faults are checked by tests in tests/multiprocess (kill -9 mid-transfer and
--resume, bad messages, unauthorized robots, 10% loss).
""")
print(f"wrote {doc}")
EOF
