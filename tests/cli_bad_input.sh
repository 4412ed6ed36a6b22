#!/usr/bin/env bash
# Every bad input must give "error: ..." on stderr naming the problem, the
# README's exit code (1: input data, 2: command line or configuration), no
# crash and no output files.
set -u
bin=$1; tmp=$2
rm -rf "$tmp"; mkdir -p "$tmp"
fails=0
expect_error() {  # expect_error NAME EXIT_CODE PATTERN -- command...
  local name=$1 expected=$2 pattern=$3; shift 4
  local out code
  out=$("$@" 2>&1 >/dev/null); code=$?
  printf '%s\n' "$out" > "$tmp/$name.err"
  if [ $code -ne "$expected" ]; then
    echo "FAIL $name: exit code $code, expected $expected"; echo "$out"; fails=$((fails + 1)); return
  fi
  if ! grep -q '^error: ' <<<"$out" || ! grep -q -- "$pattern" <<<"$out"; then
    echo "FAIL $name: no 'error: ...' naming '$pattern' on stderr:"; echo "$out"; fails=$((fails + 1)); return
  fi
  echo "ok   $name: $(grep -m 1 '^error: ' <<<"$out")"
}
printf 'FLASER 3 1.0 2.0\n' > "$tmp/truncated.log"
printf 'FLASER 3 1.0 abc 3.0 0 0 0 0 0 0 1.0 host 1.0\n' > "$tmp/corrupt.log"
: > "$tmp/empty.log"
printf 'GARBAGE\n' > "$tmp/garbage.bag"
head -c 3000 /dev/urandom | gzip > "$tmp/random.log.gz"; head -c 200 "$tmp/random.log.gz" > "$tmp/cut.log.gz"
printf '{"matcher": {"evaluations": -3}}' > "$tmp/bad_config.json"
printf '0 0 0\n' > "$tmp/bad.tum"

expect_error missing-file 1 "no_such.log" -- "$bin" run "$tmp/no_such.log" --out "$tmp/o1"
expect_error truncated-line 1 "truncated.log:1" -- "$bin" run "$tmp/truncated.log" --out "$tmp/o2"
expect_error corrupt-field 1 "corrupt.log:1" -- "$bin" run "$tmp/corrupt.log" --out "$tmp/o3"
expect_error empty-log 1 "empty.log" -- "$bin" run "$tmp/empty.log" --out "$tmp/o4"
expect_error not-a-bag 1 "garbage.bag" -- "$bin" run "$tmp/garbage.bag" --out "$tmp/o5"
expect_error truncated-gzip 1 "cut.log.gz" -- "$bin" run "$tmp/cut.log.gz" --out "$tmp/o6"
expect_error bad-config 2 "matcher.evaluations" -- "$bin" run "$tmp/truncated.log" --config "$tmp/bad_config.json" --out "$tmp/o7"
expect_error bad-option 2 "--bogus" -- "$bin" run "$tmp/truncated.log" --bogus --out "$tmp/o8"
expect_error bad-tum 1 "bad.tum:1" -- "$bin" eval ate "$tmp/bad.tum" "$tmp/bad.tum"
expect_error no-subcommand 2 "subcommand" -- "$bin"
expect_error negative-seed 2 "--seed" -- "$bin" run "$tmp/truncated.log" --seed -1 --out "$tmp/o16"
expect_error negative-run-seed 2 "--run-seed" -- "$bin" demo --run-seed -1 --out "$tmp/s6"
expect_error option-without-value 2 "--out" -- "$bin" run "$tmp/truncated.log" --out
expect_error bad-option-value 2 "--evaluations" -- "$bin" run "$tmp/truncated.log" --evaluations lots --out "$tmp/o17"
for args in "--help" "--version" "run --help" "demo --help"; do
  # shellcheck disable=SC2086  # split on purpose
  if ! out=$("$bin" $args 2>&1) || [ -z "$out" ]; then echo "FAIL dsswarm $args: not exit 0 with text"; fails=$((fails + 1)); fi
done

# .dsmap maps (--save-map / --load-map): a valid one from a tiny log, then damaged copies.
ranges=$(printf '2.0 %.0s' $(seq 180))
for t in 1 2 3; do printf 'FLASER 180 %s0 0 0 0 0 0 %d.0 host %d.0\n' "$ranges" "$t" "$t"; done > "$tmp/small.log"
if ! "$bin" run "$tmp/small.log" --out "$tmp/ok" --save-map "$tmp/good.dsmap" >/dev/null 2>&1 || [ ! -s "$tmp/good.dsmap" ]; then
  echo "FAIL save-map: no map written"; fails=$((fails + 1))
fi
cp "$tmp/good.dsmap" "$tmp/corrupt.dsmap"
printf '\x5a\x5a\x5a\x5a' | dd of="$tmp/corrupt.dsmap" bs=1 seek=40 conv=notrunc status=none
head -c 40 "$tmp/good.dsmap" > "$tmp/cut.dsmap"
printf 'P5 not a map\n' > "$tmp/text.dsmap"
expect_error dsmap-missing 1 "no_such.dsmap" -- "$bin" run "$tmp/small.log" --out "$tmp/o9" --load-map "$tmp/no_such.dsmap"
expect_error dsmap-corrupt 1 "corrupt.dsmap: checksum mismatch" -- "$bin" run "$tmp/small.log" --out "$tmp/o10" --load-map "$tmp/corrupt.dsmap"
expect_error dsmap-truncated 1 "cut.dsmap: truncated" -- "$bin" run "$tmp/small.log" --out "$tmp/o11" --load-map "$tmp/cut.dsmap"
expect_error dsmap-not-a-map 1 "text.dsmap: not a .dsmap file" -- "$bin" run "$tmp/small.log" --out "$tmp/o12" --load-map "$tmp/text.dsmap"
expect_error dsmap-resolution 1 "good.dsmap: the map has resolution 0.05 m" -- "$bin" run "$tmp/small.log" --out "$tmp/o13" --load-map "$tmp/good.dsmap" --resolution 0.1
expect_error bad-start-pose 2 "--start-pose" -- "$bin" run "$tmp/small.log" --out "$tmp/o14" --load-map "$tmp/good.dsmap" --start-pose 1 2
expect_error start-pose-commas 2 "--start-pose" -- "$bin" run "$tmp/small.log" --out "$tmp/o14" --load-map "$tmp/good.dsmap" --start-pose 1,2,3
expect_error start-pose-nan 2 "--start-pose" -- "$bin" run "$tmp/small.log" --out "$tmp/o14" --load-map "$tmp/good.dsmap" --start-pose nan 0 0
expect_error start-pose-alone 2 "load-map" -- "$bin" run "$tmp/small.log" --out "$tmp/o15" --start-pose 0 0 0
# --start-pose X Y THETA like --laser-offset X Y THETA; --load-map says what it loaded.
if ! out=$("$bin" run "$tmp/small.log" --out "$tmp/ok2" --load-map "$tmp/good.dsmap" --start-pose 0.05 0 0 2>/dev/null); then
  echo "FAIL load-map: a valid map was refused"; fails=$((fails + 1))
elif ! grep -q "^loaded map $tmp/good.dsmap: layer 0 of 1 ('robot', version 3), 3 levels, 0.05 m cells, [0-9]* cells allocated, [0-9.]* m x [0-9.]* m$" <<<"$out"; then
  echo "FAIL load-map: no line saying what was loaded:"; echo "$out"; fails=$((fails + 1))
fi
# --help shows the defaults of the SLAM options.
help=$("$bin" run --help)
for o in "--seed[^=]*=1 " "--evaluations[^=]*=240" "--resolution[^=]*=0.05"; do
  grep -q -- "$o" <<<"$help" || { echo "FAIL run --help: no default for '$o'"; fails=$((fails + 1)); }
done
# Output locations are checked before any work (the logs here are corrupt: the
# error must be about the output), never naming a temporary file.
mkdir -p "$tmp/a_dir"; : > "$tmp/a_file"
expect_error out-is-a-file 2 "--out $tmp/a_file: exists and is not a folder" -- "$bin" run "$tmp/corrupt.log" --out "$tmp/a_file"
expect_error out-in-proc 2 "--out /proc/x: cannot create a folder in /proc" -- "$bin" run "$tmp/corrupt.log" --out /proc/x
expect_error save-map-is-a-folder 2 "--save-map $tmp/a_dir: is a folder" -- "$bin" run "$tmp/corrupt.log" --out "$tmp/o18" --save-map "$tmp/a_dir"
expect_error save-map-in-proc 2 "--save-map /proc/x.dsmap" -- "$bin" run "$tmp/small.log" --out "$tmp/o19" --save-map /proc/x.dsmap
expect_error filter-out-in-proc 2 "--out /proc/f.log" -- "$bin" filter "$tmp/corrupt.log" --out /proc/f.log
expect_error filter-decisions-folder 2 "--decisions $tmp/a_dir" -- "$bin" filter "$tmp/corrupt.log" --out "$tmp/f.log" --decisions "$tmp/a_dir"
expect_error filter-plot-in-file 2 "--plot $tmp/a_file/p.png" -- "$bin" filter "$tmp/corrupt.log" --out "$tmp/f.log" --plot "$tmp/a_file/p.png"
expect_error swarm-out-is-a-file 2 "--out $tmp/a_file" -- "$bin" swarm "$tmp/broken.yaml" --out "$tmp/a_file"
expect_error demo-out-in-proc 2 "--out /proc/demo" -- "$bin" demo --out /proc/demo
if [ "$(id -u)" -ne 0 ]; then  # root writes anywhere
  mkdir -p "$tmp/locked"; chmod 555 "$tmp/locked"
  expect_error out-not-writable 2 "--out $tmp/locked" -- "$bin" run "$tmp/corrupt.log" --out "$tmp/locked"
  chmod 755 "$tmp/locked"
fi
if grep -rq '\.tmp\.' "$tmp"/*.err 2>/dev/null; then echo "FAIL: an error names a temporary file"; fails=$((fails + 1)); fi
[ -e "$tmp/f.log" ] && { echo "FAIL: filter wrote $tmp/f.log"; fails=$((fails + 1)); }

# A log without a single return (every reading at max range): a clear error, no outputs.
far=$(printf '81.91 %.0s' $(seq 180))
for t in 1 2 3; do printf 'FLASER 180 %s0 0 0 0 0 0 %d.0 host %d.0\n' "$far" "$t" "$t"; done > "$tmp/no_returns.log"
expect_error no-returns 1 "no_returns.log: no scan has a valid return" -- "$bin" run "$tmp/no_returns.log" --out "$tmp/o20" --save-map "$tmp/o20/m.dsmap"

for d in o1 o2 o3 o4 o5 o6 o7 o8 o9 o10 o11 o12 o13 o14 o15 o16 o17 o18 o19 o20; do
  if [ -e "$tmp/$d" ] && [ -n "$(ls -A "$tmp/$d")" ]; then echo "FAIL: partial outputs left in $tmp/$d"; fails=$((fails + 1)); fi
done

# Quirks of real data: warnings on stderr (stdout is for results), the run goes on.
quirky="nan -1.5 $(printf '2.0 %.0s' $(seq 178))"
for t in 1 3 2; do printf 'FLASER 180 %s0 0 0 0 0 0 %d.0 host %d.0\n' "$quirky" "$t" "$t"; done > "$tmp/quirky.log"
echo 'FOO 1 2' >> "$tmp/quirky.log"
expect_warnings() {  # expect_warnings NAME PATTERN... -- command...
  local name=$1; shift
  local patterns=()
  while [ "$1" != "--" ]; do patterns+=("$1"); shift; done; shift
  "$@" >"$tmp/stdout" 2>"$tmp/stderr" || { echo "FAIL $name: exit $?"; cat "$tmp/stderr"; fails=$((fails + 1)); return; }
  if grep -qi 'warn' "$tmp/stdout"; then echo "FAIL $name: warnings on stdout"; cat "$tmp/stdout"; fails=$((fails + 1)); return; fi
  for p in "${patterns[@]}"; do
    if ! grep -q "^warning: .*$p" "$tmp/stderr"; then echo "FAIL $name: no warning about '$p' on stderr:"; cat "$tmp/stderr"; fails=$((fails + 1)); return; fi
  done
  echo "ok   $name: $(wc -l < "$tmp/stderr") warning lines on stderr"
}
expect_warnings run-warnings "run backwards" "NaN" "negative" "unknown record type 'FOO'" -- "$bin" run "$tmp/quirky.log" --out "$tmp/w1"
expect_warnings filter-warnings "run backwards" "negative" -- "$bin" filter "$tmp/quirky.log" --out "$tmp/w2.log"

# Swarm scenarios: a typo'd key, an unknown agent in an encounter, a missing log.
printf 'agents:\n  - name: r1\n    log: corrupt.log\n    dirction: forward\n' > "$tmp/typo.yaml"
printf 'agents:\n  - name: r1\n    log: small.log\nencounters:\n  - agents: [r1, r9]\n    time: 1\n' > "$tmp/unknown_agent.yaml"
printf 'agents:\n  - name: r1\n    log: no_such.log\n' > "$tmp/missing_log.yaml"
printf 'agents: [\n' > "$tmp/broken.yaml"
expect_error swarm-typo 1 "dirction" -- "$bin" swarm "$tmp/typo.yaml" --out "$tmp/s1"
expect_error swarm-unknown-agent 1 "r9" -- "$bin" swarm "$tmp/unknown_agent.yaml" --out "$tmp/s2"
expect_error swarm-missing-log 1 "no_such.log" -- "$bin" swarm "$tmp/missing_log.yaml" --out "$tmp/s3"
expect_error swarm-broken-yaml 1 "broken.yaml" -- "$bin" swarm "$tmp/broken.yaml" --out "$tmp/s4"
expect_error demo-robots 2 "robots" -- "$bin" demo --robots 0 --out "$tmp/s5"
for d in s1 s2 s3 s4 s5 s6; do
  if [ -e "$tmp/$d" ] && [ -n "$(ls -A "$tmp/$d")" ]; then echo "FAIL: partial outputs left in $tmp/$d"; fails=$((fails + 1)); fi
done

# The swarm console says which scripted encounters could not run, and why.
fail() { echo "FAIL $*"; fails=$((fails + 1)); }
printf 'agents:\n  - name: r1\n    log: small.log\n  - name: r2\n    log: small.log\n    start: 10\nencounters:\n  - agents: [r1, r2]\n    time: 1.5\n  - agents: [r1, r2]\n    time: 11.5\n' > "$tmp/late.yaml"
out=$("$bin" swarm "$tmp/late.yaml" --out "$tmp/late" 2>/dev/null) || fail "swarm late.yaml: exit $?"
grep -qF "2 scripted encounters: 1 run, 1 skipped (r2 had not started)" <<<"$out" || fail "swarm-skipped-encounters: $out"

# demo: the README's default folder; a reused --out keeps no files of robots
# that are gone (and every file that is not dsswarm's); a run without merges
# says so instead of a worst merge error of 0.
"$bin" demo --help | grep -q 'out/demo' || fail "demo --help: default --out is not out/demo"
d=$tmp/demo; mkdir -p "$d"; echo mine > "$d/notes.txt"
"$bin" demo --robots 2 --out "$d" >/dev/null 2>&1 || fail "demo --robots 2 failed"
[ -f "$d/agents/robot2/trajectory.tum" ] && [ -f "$d/joint/robot2.tum" ] || fail "demo --robots 2: no robot2 outputs"
grep -q 'verified; waiting' "$d/encounters.json" && fail "demo: a rejected encounter's reason reads 'verified'"
grep -o '"reason": "[^"]*second encounter[^"]*"' "$d/encounters.json" | grep -v '"reason": "unconfirmed: ' && fail "demo: unconfirmed reason not saying so"
echo mine > "$d/agents/robot2/notes.txt"
out=$("$bin" demo --robots 1 --out "$d" 2>/dev/null) || fail "demo --robots 1 failed"
grep -q 'worst accepted' <<<"$out" && fail "1-robot demo reports a worst accepted transform: $out"
grep -q 'nothing was merged' <<<"$out" || fail "1-robot demo does not say nothing was merged: $out"
for f in agents/robot2/trajectory.tum agents/robot2/merged_map.png joint/robot2.tum; do
  [ -e "$d/$f" ] && fail "stale $f kept after the 1-robot demo"
done
[ -f "$d/notes.txt" ] && [ -f "$d/agents/robot2/notes.txt" ] || fail "a file dsswarm did not write was removed"
[ -f "$d/agents/robot1/trajectory.tum" ] || fail "1-robot demo wrote no robot1 outputs"

echo "$fails failed"
[ $fails -eq 0 ]
