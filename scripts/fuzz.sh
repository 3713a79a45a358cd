#!/usr/bin/env bash
# make fuzz: build the libFuzzer harnesses (fuzz/) with clang under ASan + UBSan into build-fuzz/
# and run each for FUZZ_SECONDS seconds, one process (fork mode: crashes are recorded and the
# run goes on). The seed corpus is tests/data/fuzz/<harness>/ (the regression cases that
# `make test` replays); new inputs go to build-fuzz/corpus/<harness>/, crashes, timeouts and
# out-of-memory inputs to build-fuzz/artifacts/<harness>/.
# Usage: scripts/fuzz.sh SECONDS [harness ...]   (harnesses: design nurbs meshops; default all three)
set -eu
secs=${1:-60}
shift || true
targets=${*:-design nurbs meshops}
cc=${FUZZ_CC:-clang}
out=build-fuzz
mkdir -p "$out"
san="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
cflags="-std=c11 -g -O1 -DRG2_DESIGN_MAX_POINTS=200000 -DRG2_DESIGN_MAX_PATCHES=50000 -Iinclude -Ifuzz $(pkg-config --cflags libcjson libpng)"
libs="$(pkg-config --libs libcjson libpng) -lm"
# the library once, instrumented for coverage
objs=""
for src in src/*.c fuzz/harness.c; do
  obj="$out/$(basename "${src%.c}").o"
  if [ ! -e "$obj" ] || [ "$src" -nt "$obj" ] || [ -n "$(find include src fuzz -newer "$obj" -name '*.h' 2>/dev/null | head -1)" ]; then
    $cc $cflags $san -fsanitize=fuzzer-no-link -c "$src" -o "$obj"
  fi
  objs="$objs $obj"
done
for t in $targets; do
  $cc $cflags $san -fsanitize=fuzzer "fuzz/fuzz_$t.c" $objs $libs -o "$out/fuzz_$t"
done
[ "$secs" = 0 ] && exit 0
for t in $targets; do
  mkdir -p "$out/corpus/$t" "$out/artifacts/$t"
  dict=""
  [ -f "fuzz/$t.dict" ] && dict="-dict=fuzz/$t.dict"
  echo "fuzz: $t for $secs s (log: $out/fuzz_$t.log)"
  "$out/fuzz_$t" "$out/corpus/$t" "tests/data/fuzz/$t" $dict -max_total_time="$secs" -max_len=8192 \
    -timeout=20 -rss_limit_mb=2560 -malloc_limit_mb=2048 -fork=1 -ignore_crashes=1 -ignore_timeouts=1 \
    -ignore_ooms=1 -artifact_prefix="$out/artifacts/$t/" -print_final_stats=1 >"$out/fuzz_$t.log" 2>&1 || true
  execs=$(grep -o 'exec/s\|#[0-9]*' "$out/fuzz_$t.log" | grep '^#' | tail -1 | tr -d '#')
  echo "fuzz: $t: ${execs:-?} executions; artifacts: $(ls "$out/artifacts/$t" | wc -l)"
done
