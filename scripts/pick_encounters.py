#!/usr/bin/env python3
"""Writes a two-robot `dsswarm swarm` scenario for a real log, with encounters
picked from the benchmark relations (python3 standard library only).

  scripts/pick_encounters.py split intel > scenarios/intel-split.yaml
  scripts/pick_encounters.py forward-backward intel > scenarios/intel-forward-backward.yaml

Run from the repository root (the data is read from ../shared/data).

split: robot1 plays [0, 60%] of the log, robot2 [40%, 100%], both forward.
  The seed is a relation (t1, t2) with t1 in robot1's segment only and t2 in
  robot2's only, whose poses are under 2 m apart, at least 60 s into both
  robots' runs. The start times make robot2 play t2 at the very session time
  robot1 plays t1 (robot2 joins later where the relations allow; where the
  segments meet only at revisits more than 40% of the log apart, robot1 has
  to). Both then play at the same pace, so their log-time offset is fixed:
  further encounters are the moments (robot1 at a relation timestamp) at which
  the relations put robot2 under 2 m away, 60 s or more into both runs. Of all
  seeds, the one giving the most moments at least 21 s apart wins (an accepted
  merge makes the session skip the next 20 s); closer moments fill up to 3 as
  retries should an encounter be rejected.

forward-backward: robot1 plays [0, 55%] forward, robot2 [45%, 100%] backward,
  both from session time 0; they pass each other in the middle of the log.
  Encounters are the moments in the overlap where the relations put the two
  under 2 m apart (up to 3; they are near for a few seconds only, so the later
  ones are retries).

The truth is found as `dsswarm eval swarm` finds it (src/eval/swarm_eval.hpp):
the same scan, or the shortest chain of at most 4 relations joining the two
timestamps, or, when a scan exchanged is no relation's timestamp, the same
between the relation timestamps nearest to them (within 2 s). Preferred are
encounters checked exactly at the scans exchanged, then fewer relations
chained, then nearer robots. The session clock, segment bounds and the moment
an encounter fires mirror src/apps/swarm_scenario.cpp and
src/swarm/swarm_session.cpp, with the start times as written (3 decimals), so
each robot has just played the scan its log time names when the encounter
fires (src/apps/swarm_scenario_test.cpp checks that on the shipped files).
"""
import argparse
import bisect
import collections
import gzip
import math
import sys

MAX_DT = 0.001       # s: relation timestamps match scan timestamps within this (as `eval relations`)
MAX_HOPS = 4         # longest relation chain accepted as truth (as `eval swarm`)
BRIDGE = 2.0         # s: how far from the exchanged scans `eval swarm` may check an encounter
MAX_DISTANCE = 2.0   # m: robots this close count as near (the proximity range is 3 m)
MIN_MAPPING = 60.0   # s: both robots have mapped at least this long at the first split encounter
MIN_SPACING = 21.0   # s of session time between encounters (an accepted merge blocks the next 20 s)...
RETRY_SPACINGS = (2.0, 0.4)  # ...or these, if the relations allow no more (retries should the first be rejected)
MAX_ENCOUNTERS = 3
BOUND_SLACK = 1e-6   # as swarm_scenario.cpp


# ------------------------------------------------------------------ inputs

def read_scan_times(path):
    """FLASER timestamps in file order."""
    times = []
    with gzip.open(path, "rt") if path.endswith(".gz") else open(path) as f:
        for line in f:
            if not line.startswith("FLASER"):
                continue
            fields = line.split()
            n = int(fields[1])
            times.append(float(fields[2 + n + 6]))
    return times


def read_relations(path):
    rels = []
    with open(path) as f:
        for line in f:
            fields = line.split()
            if not fields or fields[0].startswith("#"):
                continue
            if fields[0] == "FLOAT":
                fields = fields[1:]
            t1, t2, x, y = (float(v) for v in fields[:4])
            rels.append((t1, t2, (x, y, float(fields[7]))))
    return rels


# ------------------------------------------------------------------ SE(2)

def compose(a, b):
    c, s = math.cos(a[2]), math.sin(a[2])
    return (a[0] + c * b[0] - s * b[1], a[1] + s * b[0] + c * b[1], norm(a[2] + b[2]))


def inverse(a):
    c, s = math.cos(a[2]), math.sin(a[2])
    return (-(c * a[0] + s * a[1]), s * a[0] - c * a[1], norm(-a[2]))


def norm(t):
    return math.remainder(t, 2 * math.pi)


class RelationGraph:
    """Same rule as RelationGraph in src/eval/swarm_eval.cpp."""

    def __init__(self, rels):
        self.rels = rels
        times = sorted(t for r in rels for t in r[:2])
        self.nodes = []
        for t in times:
            if not self.nodes or t - self.nodes[-1] > MAX_DT:
                self.nodes.append(t)
        self.edges = collections.defaultdict(list)
        for i, (t1, t2, _) in enumerate(rels):
            n1, n2 = self.node(t1), self.node(t2)
            if n1 is None or n2 is None or n1 == n2:
                continue
            self.edges[n1].append((n2, i, True))
            self.edges[n2].append((n1, i, False))

    def endpoints_near(self, t, window):
        lo = bisect.bisect_left(self.nodes, t - window)
        hi = bisect.bisect_right(self.nodes, t + window)
        return sorted(self.nodes[lo:hi], key=lambda n: abs(n - t))  # stable: the earlier first on a tie

    def node(self, t):
        k = bisect.bisect_right(self.nodes, t)
        best = None
        for j in (k, k - 1):
            if 0 <= j < len(self.nodes) and abs(self.nodes[j] - t) <= MAX_DT:
                if best is None or abs(self.nodes[j] - t) < abs(self.nodes[best] - t):
                    best = j
        return best

    def truth(self, ta, tb):
        """(motion from ta to tb in ta's frame, hops) or None."""
        if abs(ta - tb) <= MAX_DT:
            return (0.0, 0.0, 0.0), 0
        a, b = self.node(ta), self.node(tb)
        if a is None or b is None:
            return None
        if a == b:
            return (0.0, 0.0, 0.0), 0
        parent = {a: None}
        frontier = [a]
        for _ in range(MAX_HOPS):
            nxt = []
            for n in frontier:
                for (m, i, fwd) in self.edges[n]:
                    if m not in parent:
                        parent[m] = (n, i, fwd)
                        nxt.append(m)
            frontier = nxt
            if b in parent:
                break
        if b not in parent:
            return None
        path = []
        n = b
        while parent[n] is not None:
            prev, i, fwd = parent[n]
            path.append((i, fwd))
            n = prev
        motion = (0.0, 0.0, 0.0)
        for i, fwd in reversed(path):
            r = self.rels[i][2]
            motion = compose(motion, r if fwd else inverse(r))
        return motion, len(path)


# ------------------------------------------------------------------ playback

class Agent:
    """An agent's scans in play order and session clock, as swarm_scenario.cpp builds them."""

    def __init__(self, times, lo_fraction, hi_fraction, backward, start):
        running, m = [], -math.inf
        for t in times:
            m = max(m, t)
            running.append(m)
        t0, duration = times[0], running[-1] - times[0]
        lo = t0 + lo_fraction * duration - BOUND_SLACK
        hi = t0 + hi_fraction * duration + BOUND_SLACK
        idx = [i for i, r in enumerate(running) if lo <= r <= hi]
        if backward:
            idx.reverse()
        self.stamps = [times[i] for i in idx]
        self.lo_time, self.hi_time = min(self.stamps), max(self.stamps)
        self.first = self.stamps[0]
        sign = -1.0 if backward else 1.0
        self.clocks, e = [], 0.0
        for t in self.stamps:
            e = max(e, sign * (t - self.first))
            self.clocks.append(start + e)  # the same sum as the loader's, so the same doubles
        self.start = start
        self.by_time = sorted((t, i) for i, t in enumerate(self.stamps))

    def clock(self, i):
        return self.clocks[i]

    def index_at_log_time(self, t):
        """Nearest scan by timestamp; on a tie, the first in play order (as the loader)."""
        k = bisect.bisect_left(self.by_time, (t, -1))
        near = [self.by_time[j] for j in (k - 1, k) if 0 <= j < len(self.by_time)]
        best = min(abs(s - t) for s, _ in near)
        # Equal timestamps sit together in by_time; gather all at the best distance.
        ties = [i for s, i in self.by_time[max(0, k - 3):k + 3] if abs(s - t) == best]
        return min(ties)

    def plays(self, t):
        k = bisect.bisect_left(self.by_time, (t - MAX_DT, -1))
        return k < len(self.by_time) and self.by_time[k][0] <= t + MAX_DT

    def log_time_at(self, session_time):
        """Last scan played by `session_time` (SwarmSession plays every scan with clock <= the event's time)."""
        k = bisect.bisect_right(self.clocks, session_time)
        return self.stamps[k - 1] if k > 0 else None


def bridge_time(graph, agent, t):
    """The relation timestamp nearest to t (within BRIDGE) that the agent plays, as `eval swarm` picks it."""
    for c in graph.endpoints_near(t, BRIDGE):
        if agent.plays(c):
            return c
    return None


def encounter_at(r1, r2, x, graph):
    """The encounter when robot1 plays log time x, if robot2 is then near by relation truth:
    (session time, x, y, distance, hops, shift), y being robot2's log time and shift how far
    from x and y `eval swarm` will check it (0: exactly there)."""
    time = r1.clock(r1.index_at_log_time(x))
    y = r2.log_time_at(time)
    if y is None:
        return None
    t, shift = graph.truth(x, y), 0.0
    if t is None:
        xa, yb = bridge_time(graph, r1, x), bridge_time(graph, r2, y)
        if xa is None or yb is None:
            return None
        t, shift = graph.truth(xa, yb), max(abs(xa - x), abs(yb - y))
    if t is None:
        return None
    motion, hops = t
    distance = math.hypot(motion[0], motion[1])
    if distance >= MAX_DISTANCE:
        return None
    return (time, x, y, distance, hops, shift)


def spaced(candidates, chosen=()):
    """Up to MAX_ENCOUNTERS encounters in time order: `chosen`, then candidates at least
    MIN_SPACING from every other (so each is a separate measurement), or failing that at least
    RETRY_SPACINGS (a retry while the robots are still near, should the first be rejected).
    Preferred: truth exactly at the scans exchanged, then fewest relations chained, then nearest."""
    chosen = list(chosen)
    ranked = sorted(candidates, key=lambda c: (c[5] > 0, c[4], c[3], c[0]))
    for spacing in (MIN_SPACING,) + RETRY_SPACINGS:
        for c in ranked:
            if len(chosen) == MAX_ENCOUNTERS:
                break
            if all(abs(c[0] - d[0]) >= spacing for d in chosen):
                chosen.append(c)
    return sorted(chosen)


# ------------------------------------------------------------------ scenarios

def pick_split(times, rels, graph, args):
    probe1 = Agent(times, 0.0, args.overlap_hi, False, 0.0)
    probe2 = Agent(times, args.overlap_lo, 1.0, False, 0.0)
    only1 = lambda t: probe1.lo_time <= t < probe2.lo_time
    only2 = lambda t: probe1.hi_time < t <= probe2.hi_time
    endpoints1 = sorted({t for r in rels for t in r[:2] if only1(t)})
    seeds = []
    for (t1, t2, m) in rels:
        if only2(t1) and only1(t2):
            t1, t2, m = t2, t1, inverse(m)
        if not (only1(t1) and only2(t2)):
            continue
        d = math.hypot(m[0], m[1])
        mapped1 = t1 - probe1.first
        mapped2 = t2 - probe2.first
        if d < MAX_DISTANCE and mapped1 >= MIN_MAPPING and mapped2 >= MIN_MAPPING:
            seeds.append((t1, t2, d))
    if not seeds:
        sys.exit("no relation links the two segments with both robots mapping for a minute")
    best = None
    for (t1, t2, d) in seeds:
        # robot2 plays t2 when robot1 plays t1; 1 ms early so t2 is surely played by then.
        gap = probe1.clock(probe1.index_at_log_time(t1)) - probe2.clock(probe2.index_at_log_time(t2))
        start1 = round(max(0.0, -gap) + (0.001 if gap < 0 else 0.0), 3)
        start2 = round(max(0.0, gap - 0.001), 3)
        r1 = Agent(times, 0.0, args.overlap_hi, False, start1)
        r2 = Agent(times, args.overlap_lo, 1.0, False, start2)
        first = encounter_at(r1, r2, t1, graph)
        if first is None or abs(first[2] - t2) > MAX_DT or first[5] > 0:
            continue  # rounding moved robot2 off t2
        # Every encounter with both robots mapping for a minute, not only the seed.
        others = [e for x in endpoints1 if (e := encounter_at(r1, r2, x, graph)) and only2(e[2])
                  and e[0] - max(start1, start2) >= MIN_MAPPING]
        picked = spaced(others, [first])
        # robot1 starting the session (robot2 joins later) where possible; then most separate
        # moments, most encounters, most checked exactly at the scans exchanged; then the seed
        # where both robots have mapped longest (the shorter of the two runs).
        exact = sum(1 for e in picked if e[5] == 0)
        apart = sum(1 for a, b in zip(picked, picked[1:]) if b[0] - a[0] >= MIN_SPACING)
        key = (start1 == 0.0, apart, len(picked), exact, min(t1 - r1.first, t2 - r2.first), -d)
        if best is None or key > best[0]:
            best = (key, (t1, t2, d), start1, start2, picked)
    if best is None:
        sys.exit("no usable offset found")
    _, seed, start1, start2, picked = best
    agents = [
        ("robot1", f"to_fraction: {args.overlap_hi}", "forward", start1),
        ("robot2", f"from_fraction: {args.overlap_lo}", "forward", start2),
    ]
    how = [
        f"robot1 plays [0, {args.overlap_hi:.0%}] of the log, robot2 [{args.overlap_lo:.0%}, 100%], both forward.",
        "Picked by scripts/pick_encounters.py from the relations: the seed relation",
        f"  {seed[0]:.6f} -> {seed[1]:.6f} ({seed[2]:.2f} m) has t1 only in robot1's segment and t2 only in",
        f"  robot2's, both robots mapping >= {MIN_MAPPING:.0f} s by then; the start times make robot2 play t2 at",
        "  the session time robot1 plays t1. " + (
            f"robot2 joins {start2:.0f} s after robot1." if start1 == 0.0 else
            f"robot1 has to join {start1:.0f} s after robot2: the segments meet only where the robot"
        ),
    ] + ([] if start1 == 0.0 else [
        f"  revisited a place {seed[1] - seed[0]:.0f} s later in the log, more than robot2's head start allows."
    ]) + [
        "  The two then keep that log-time offset; the other encounters (also >= 60 s into both runs) are",
        f"  moments where the relations put them < {MAX_DISTANCE:.0f} m apart (truth as `dsswarm eval swarm`",
        f"  finds it: one relation or a chain of <= {MAX_HOPS}). Of all seeds, the one with the most moments",
        f"  >= {MIN_SPACING:.0f} s apart won (closer ones are retries should an encounter be rejected).",
    ]
    return agents, picked, how


def pick_forward_backward(times, rels, graph, args):
    r1 = Agent(times, 0.0, args.overlap_hi, False, 0.0)
    r2 = Agent(times, args.overlap_lo, 1.0, True, 0.0)
    overlap = lambda t: r2.lo_time <= t <= r1.hi_time
    # Every scan robot1 plays in the overlap is a candidate moment (truth through the bridge).
    moments = [x for x in r1.stamps if overlap(x)]
    candidates = [e for x in moments if (e := encounter_at(r1, r2, x, graph)) and overlap(e[2])]
    if not candidates:
        sys.exit("no moment in the overlap where the two robots are near by relation truth")
    picked = spaced(candidates)
    agents = [
        ("robot1", f"to_fraction: {args.overlap_hi}", "forward", 0.0),
        ("robot2", f"from_fraction: {args.overlap_lo}", "backward", 0.0),
    ]
    how = [
        f"robot1 plays [0, {args.overlap_hi:.0%}] of the log forward, robot2 [{args.overlap_lo:.0%}, 100%] backward",
        "  (from the end), both from session time 0: they pass each other in the middle of the log.",
        "Picked by scripts/pick_encounters.py from the relations: moments in the overlap where the relations",
        f"  put the two robots < {MAX_DISTANCE:.0f} m apart (truth as `dsswarm eval swarm` finds it: the same scan,",
        f"  or a chain of <= {MAX_HOPS} relations, checked at relation timestamps <= {BRIDGE:.0f} s away when the",
        "  scans exchanged are none). The robots are near for a few seconds only, so the later ones are retries",
        "  should the first be rejected (after an accepted merge the session skips them).",
    ]
    return agents, picked, how


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("mode", choices=["split", "forward-backward"])
    p.add_argument("log", help="dataset name: intel, fr079, mit-csail")
    p.add_argument("--data", default="../shared/data", help="where the data is, from the current folder")
    p.add_argument("--data-from-scenario", default="../../shared/data",
                   help="the same folder as the scenario file names it (scenarios/ -> ../../shared/data)")
    p.add_argument("--overlap-lo", type=float, default=None, help="robot2's segment starts here (fraction)")
    p.add_argument("--overlap-hi", type=float, default=None, help="robot1's segment ends here (fraction)")
    args = p.parse_args()
    if args.overlap_lo is None:
        args.overlap_lo = 0.4 if args.mode == "split" else 0.45
    if args.overlap_hi is None:
        args.overlap_hi = 0.6 if args.mode == "split" else 0.55

    times = read_scan_times(f"{args.data}/carmen/{args.log}.log.gz")
    rels = read_relations(f"{args.data}/relations/{args.log}.relations")
    graph = RelationGraph(rels)
    pick = pick_split if args.mode == "split" else pick_forward_backward
    agents, picked, how = pick(times, rels, graph, args)

    out = [f"# {args.log}, experiment {'1' if args.mode == 'split' else '2'} ({args.mode}): written by",
           f"#   scripts/pick_encounters.py {args.mode} {args.log}"]
    out += ["# " + line for line in how]
    out += [f"name: {args.log}-{args.mode}",
            f"relations: {args.data_from_scenario}/relations/{args.log}.relations",
            "agents:"]
    for (name, bound, direction, start) in agents:
        out += [f"  - name: {name}",
                f"    log: {args.data_from_scenario}/carmen/{args.log}.log.gz",
                f"    {bound}",
                f"    direction: {direction}",
                f"    start: {start:.3f}"]
    out.append("encounters:")
    for (time, x, y, distance, hops, shift) in picked:
        truth = "the same scan" if hops == 0 else ("one relation" if hops == 1 else f"a chain of {hops} relations")
        where = f", checked {shift:.2f} s away" if shift > 0 else ""
        out += [f"  # session time {time:.3f} s; {distance:.2f} m apart by {truth}{where}",
                "  - agents: [robot1, robot2]",
                f"    log_times: [{x:.6f}, {y:.6f}]"]
    print("\n".join(out))
    for (time, x, y, distance, hops, shift) in picked:
        print(f"{args.log} {args.mode}: t={time:9.3f}  {x:.6f} -> {y:.6f}  {distance:.2f} m  hops {hops}"
              f"  shift {shift:.2f} s",
              file=sys.stderr)


if __name__ == "__main__":
    main()
