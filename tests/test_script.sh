#!/usr/bin/env bash
# scripts/test.sh must run the normal tests even right after scripts/demo.sh
# configured the same build folder without them, and every ctest call must
# fail when it finds no test. Runs the two scripts against stand-ins for
# cmake, ctest and install_deps.sh; the cmake stand-in keeps a cache per build
# folder as CMake does (a -D option stays set until set again).
set -u
src=$1; tmp=$2
rm -rf "$tmp"; mkdir -p "$tmp/repo/scripts" "$tmp/bin"
cp "$src/scripts/test.sh" "$src/scripts/demo.sh" "$tmp/repo/scripts/"
printf '#!/bin/sh\nexit 0\n' > "$tmp/repo/scripts/install_deps.sh"
cat > "$tmp/bin/cmake" <<'STUB'
#!/usr/bin/env bash
# cmake -S . -B DIR -DKEY=VALUE...: remembers the options in DIR/cache;
# cmake --build DIR ...: leaves a dsswarm stand-in there.
if [ "$1" = "--build" ]; then
  printf '#!/bin/sh\nexit 0\n' > "$2/dsswarm"; chmod +x "$2/dsswarm"; exit 0
fi
dir=""
while [ $# -gt 0 ]; do
  case $1 in
    -B) dir=$2; shift ;;
    -D*) mkdir -p "$dir"; key=${1#-D}; key=${key%%=*}
         { grep -v "^$key=" "$dir/cache" 2>/dev/null; echo "${1#-D}"; } > "$dir/cache.new"
         mv "$dir/cache.new" "$dir/cache" ;;
  esac
  shift
done
mkdir -p "$dir"; touch "$dir/cache"
STUB
cat > "$tmp/bin/ctest" <<'STUB'
#!/usr/bin/env bash
# Finds tests unless the folder was configured with DSSWARM_BUILD_TESTS=OFF
# (the option defaults to ON); like ctest, passes without tests unless
# --no-tests=error is given.
tests=1
grep -q '^DSSWARM_BUILD_TESTS=OFF' cache 2>/dev/null && tests=0
echo "$(basename "$PWD") tests=$tests args=$*" >> "$LOG"
if [ $tests -eq 0 ]; then
  echo "No tests were found!!!"
  for a in "$@"; do [ "$a" = "--no-tests=error" ] && exit 8; done
fi
exit 0
STUB
chmod +x "$tmp/bin/cmake" "$tmp/bin/ctest" "$tmp/repo/scripts/"*.sh
export PATH="$tmp/bin:$PATH" LOG="$tmp/ctest.log"
fails=0
fail() { echo "FAIL $*"; fails=$((fails + 1)); }

(cd "$tmp/repo" && scripts/demo.sh >/dev/null) || fail "demo.sh failed"
: > "$LOG"
(cd "$tmp/repo" && scripts/test.sh >/dev/null) || fail "test.sh failed after demo.sh"
cat "$LOG"
grep -q '^build tests=1' "$LOG" || fail "test.sh after demo.sh ran no test in build/"
while read -r line; do
  grep -q -- '--no-tests=error' <<<"$line" || fail "ctest call without --no-tests=error: $line"
done < "$LOG"
[ -s "$LOG" ] || fail "test.sh called no ctest"
echo "$fails failed"
[ $fails -eq 0 ]
