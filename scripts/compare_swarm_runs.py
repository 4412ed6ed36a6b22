#!/usr/bin/env python3
"""Compares two swarm runs of one scenario encounter by encounter.

Usage: scripts/compare_swarm_runs.py REFERENCE_DIR OTHER_DIR [--until SECONDS]

Each directory holds an encounters.json (`dsswarm swarm`/`demo` or
`dsswarm launch`). Typically the reference is the in-process run and the
other the same scenario as robot processes. Prints which encounters ran in
both, how many decisions are equal, how far the transforms accepted by both
differ, the decisions that differ, and the wrong merges of each run (accepted
and off by more than 0.3 m or 3 degrees under both references, as `eval`
scores them).
"""
import argparse
import json
import math
import sys


def load(run_dir):
    try:
        with open(f"{run_dir}/encounters.json") as f:
            encounters = json.load(f)["encounters"]
    except (OSError, KeyError, json.JSONDecodeError) as e:
        sys.exit(f"{run_dir}/encounters.json: cannot read: {e}")
    return {(e["id"], "-".join(e["agents"])): e for e in encounters}


def difference(t, u):
    """Translation (m) and rotation (deg) of u relative to t, both (x, y, theta)."""
    c, s = math.cos(t[2]), math.sin(t[2])
    dx, dy = u[0] - t[0], u[1] - t[1]
    x, y = c * dx + s * dy, -s * dx + c * dy
    dtheta = math.atan2(math.sin(u[2] - t[2]), math.cos(u[2] - t[2]))
    return math.hypot(x, y), abs(math.degrees(dtheta))


def wrong(e):
    beyond = lambda err: err[0] > 0.3 or err[1] > 3.0  # (metres, degrees)
    return e.get("accepted") and "error" in e and beyond(e["error"]) and beyond(e["aligned_error"])


def outcome(e):
    return "accepted" if e["accepted"] else "not merged (" + e.get("reason", "") + ")"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("reference")
    parser.add_argument("other")
    parser.add_argument("--until", type=float, default=math.inf, help="only encounters before this time (s)")
    a = parser.parse_args()
    ref = {k: e for k, e in load(a.reference).items() if e["time"] < a.until}
    other = {k: e for k, e in load(a.other).items() if e["time"] < a.until}
    both = sorted(set(ref) & set(other))
    equal = [k for k in both if ref[k]["accepted"] == other[k]["accepted"]]
    accepted_both = [k for k in both if ref[k]["accepted"] and other[k]["accepted"]]
    diffs = [difference(ref[k]["transform"], other[k]["transform"]) for k in accepted_both]
    print(f"encounters: {len(ref)} in {a.reference}, {len(other)} in {a.other}, {len(both)} in both")
    print(f"decisions equal: {len(equal)} of {len(both)}; accepted: {sum(e['accepted'] for e in ref.values())} "
          f"against {sum(e['accepted'] for e in other.values())}, {len(accepted_both)} by both")
    if diffs:
        print(f"accepted by both, transform difference: worst {1000 * max(d[0] for d in diffs):.1f} mm / "
              f"{max(d[1] for d in diffs):.3f} deg, median {1000 * sorted(d[0] for d in diffs)[len(diffs) // 2]:.1f} mm")
    for k in both:
        if k not in equal:
            print(f"  differs: encounter {k[0]} {k[1]} at {ref[k]['time']:.1f} s: {outcome(ref[k])} | {outcome(other[k])}")
    for k in sorted(set(ref) ^ set(other)):
        print(f"  only in {a.reference if k in ref else a.other}: encounter {k[0]} {k[1]}")
    for name, run in ((a.reference, ref), (a.other, other)):
        bad = sorted(k for k, e in run.items() if wrong(e))
        print(f"wrong merges in {name}: {len(bad)}" +
              "".join(f"\n  encounter {k[0]} {k[1]} at {run[k]['time']:.1f} s, error {run[k]['error'][0]:.3f} m" for k in bad))


if __name__ == "__main__":
    main()
