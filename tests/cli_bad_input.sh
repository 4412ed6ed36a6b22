#!/usr/bin/env bash
# Every bad input must give "error: ..." naming the problem, a non-zero exit,
# no crash (exit >= 128) and no output files.
set -u
bin=$1; tmp=$2
rm -rf "$tmp"; mkdir -p "$tmp"
fails=0
expect_error() {  # expect_error NAME PATTERN -- command...
  local name=$1 pattern=$2; shift 3
  local out code
  out=$("$@" 2>&1); code=$?
  if [ $code -eq 0 ] || [ $code -ge 128 ]; then
    echo "FAIL $name: exit code $code"; echo "$out"; fails=$((fails + 1)); return
  fi
  if ! grep -q -- "$pattern" <<<"$out"; then
    echo "FAIL $name: message lacks '$pattern':"; echo "$out"; fails=$((fails + 1)); return
  fi
  echo "ok   $name: $(head -n 1 <<<"$out")"
}
printf 'FLASER 3 1.0 2.0\n' > "$tmp/truncated.log"
printf 'FLASER 3 1.0 abc 3.0 0 0 0 0 0 0 1.0 host 1.0\n' > "$tmp/corrupt.log"
: > "$tmp/empty.log"
printf 'GARBAGE\n' > "$tmp/garbage.bag"
head -c 3000 /dev/urandom | gzip > "$tmp/random.log.gz"; head -c 200 "$tmp/random.log.gz" > "$tmp/cut.log.gz"
printf '{"matcher": {"evaluations": -3}}' > "$tmp/bad_config.json"
printf '0 0 0\n' > "$tmp/bad.tum"

expect_error missing-file "no_such.log" -- "$bin" run "$tmp/no_such.log" --out "$tmp/o1"
expect_error truncated-line "truncated.log:1" -- "$bin" run "$tmp/truncated.log" --out "$tmp/o2"
expect_error corrupt-field "corrupt.log:1" -- "$bin" run "$tmp/corrupt.log" --out "$tmp/o3"
expect_error empty-log "empty.log" -- "$bin" run "$tmp/empty.log" --out "$tmp/o4"
expect_error not-a-bag "garbage.bag" -- "$bin" run "$tmp/garbage.bag" --out "$tmp/o5"
expect_error truncated-gzip "cut.log.gz" -- "$bin" run "$tmp/cut.log.gz" --out "$tmp/o6"
expect_error bad-config "matcher.evaluations" -- "$bin" run "$tmp/truncated.log" --config "$tmp/bad_config.json" --out "$tmp/o7"
expect_error bad-option "--bogus" -- "$bin" run "$tmp/truncated.log" --bogus --out "$tmp/o8"
expect_error bad-tum "bad.tum:1" -- "$bin" eval ate "$tmp/bad.tum" "$tmp/bad.tum"
expect_error no-subcommand "subcommand" -- "$bin"
for d in o1 o2 o3 o4 o5 o6 o7 o8; do
  if [ -e "$tmp/$d" ] && [ -n "$(ls -A "$tmp/$d")" ]; then echo "FAIL: partial outputs left in $tmp/$d"; fails=$((fails + 1)); fi
done
echo "$fails failed"
[ $fails -eq 0 ]
