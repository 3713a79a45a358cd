#!/usr/bin/env bash
# Cross build + the ctest suite under qemu-user, on a Debian/Ubuntu x86-64 machine (an optional
# `make check-cross`): the library, the rg2 command and the tests for another architecture,
# built with a Debian cross GCC and run through qemu-user.
#   aarch64  little-endian 64-bit (Apple silicon / Raspberry Pi / Graviton class)
#   s390x    big-endian 64-bit
#   i686     32-bit (size_t of 32 bits)
# Usage: scripts/check_cross.sh <source-dir> <build-root> <arch> [extra cmake options...]
#   e.g. scripts/check_cross.sh . /tmp/cross s390x -DRG2_OPENMP=OFF
# Environment: CROSS_JOBS (default 2), CROSS_TIMEOUT (per test, seconds, default 1800),
#   CROSS_TESTS (a ctest -R regex, default all), CROSS_REUSE=1 (keep an existing build tree).
# As root it installs what it needs with apt-get (idempotent): the cross compiler and qemu-user
# (host packages). The target's libcjson/libpng/zlib are NOT installed through dpkg multiarch:
# `apt-get download` fetches the target .debs and they are unpacked into <build-root>/sysroot-<arch>,
# so the system's package set is unchanged (multiarch also refuses whenever the mirror's foreign
# index is a security update behind the host's, which happens) and nothing needs purging after;
# only the architecture's package index is added where missing (dpkg --remove-architecture undoes it).
# Known artefacts of emulation (not of rg2): under qemu-user 7.2 a forked child of a threaded
# program aborts in qemu (test_pool: "qemu_plugin_vcpu_init_hook: assertion failed"), and on s390x
# the host's localedef writes a little-endian locale the big-endian guest cannot load (test_locale,
# test_threads: "de_DE.UTF-8 could not be made"). test_fptraps skips where traps do not exist (aarch64).
# The bash-driven CLI tests (tests/cli/*.sh) run the rg2 binary directly, which needs binfmt_misc;
# where that is missing (containers) the built rg2 is replaced by a wrapper that runs it in qemu.
set -eu
[ $# -ge 3 ] || { echo "usage: $0 <source-dir> <build-root> <aarch64|s390x|i686> [cmake options]" >&2; exit 2; }
src=$(cd "$1" && pwd) root=$2 arch=$3; shift 3
mkdir -p "$root" && root=$(cd "$root" && pwd)
case $arch in
  aarch64|arm64) arch=aarch64 triple=aarch64-linux-gnu deb=arm64 qemu=qemu-aarch64 multi=aarch64-linux-gnu ;;
  s390x)         triple=s390x-linux-gnu deb=s390x qemu=qemu-s390x multi=s390x-linux-gnu ;;
  i686|i386)     arch=i686 triple=i686-linux-gnu deb=i386 qemu=qemu-i386 multi=i386-linux-gnu ;;
  *) echo "check-cross: unknown arch $arch (aarch64, s390x, i686)" >&2; exit 2 ;;
esac
multi=$(dpkg-architecture -a "$deb" -qDEB_HOST_MULTIARCH 2>/dev/null || echo "$multi") # (Debian's library directory)
jobs=${CROSS_JOBS:-2}
start=$(date +%s)

need=()
[ -e "/usr/$triple/lib/crti.o" ] && command -v "$triple-gcc" >/dev/null || need+=("gcc-$triple" "libc6-dev-$deb-cross")
command -v "$qemu" >/dev/null || need+=(qemu-user)
command -v pkg-config >/dev/null || need+=(pkg-config)
command -v cmake >/dev/null || need+=(cmake)
if [ ${#need[@]} -gt 0 ]; then
  [ "$(id -u)" = 0 ] || { echo "check-cross: missing ${need[*]} (run as root to install)" >&2; exit 1; }
  echo "check-cross: apt-get install ${need[*]}"
  apt-get update -q >/dev/null || true
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${need[@]}" >/dev/null
fi

sysroot=$root/sysroot-$arch
if [ ! -f "$sysroot/.done" ]; then
  echo "check-cross: target libraries ($deb) into $sysroot"
  rm -rf "$sysroot" "$root/debs-$arch" && mkdir -p "$sysroot" "$root/debs-$arch"
  fetch() { (cd "$root/debs-$arch" &&
    apt-get download -q libcjson1:"$deb" libcjson-dev:"$deb" libpng16-16:"$deb" libpng-dev:"$deb" \
      zlib1g:"$deb" zlib1g-dev:"$deb" >/dev/null 2>&1); }
  # apt-get download needs the architecture's package index: added (as root) only where missing
  if ! fetch; then
    if [ "$(id -u)" = 0 ] && ! dpkg --print-foreign-architectures | grep -qx "$deb"; then
      echo "check-cross: dpkg --add-architecture $deb (undo: dpkg --remove-architecture $deb; nothing of $deb is installed)"
      if dpkg --add-architecture "$deb"; then apt-get update -q >/dev/null 2>&1 || true; fi
    fi
    fetch || { echo "check-cross: apt-get download of the $deb libraries failed: it needs the $deb package index" >&2
      echo "  (dpkg --add-architecture $deb && apt-get update, as root)" >&2; exit 1; }
  fi
  for d in "$root/debs-$arch"/*.deb; do dpkg-deb -x "$d" "$sysroot"; done
  touch "$sysroot/.done"
fi
libdir=$sysroot/usr/lib/$multi
rpath="-Wl,--disable-new-dtags -Wl,-rpath,$libdir -Wl,-rpath-link,$libdir -Wl,-rpath,$sysroot/lib/$multi -Wl,-rpath-link,$sysroot/lib/$multi"

tc=$root/toolchain-$arch.cmake
cat >"$tc" <<EOF
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR $arch)
set(CMAKE_C_COMPILER $triple-gcc)
set(CMAKE_FIND_ROOT_PATH /usr/$triple $sysroot)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
set(CMAKE_CROSSCOMPILING_EMULATOR $qemu;-L;/usr/$triple)
# the unpacked target libraries (zlib in lib/, the others in usr/lib/): found at link time and,
# through the rpath, under qemu (DT_RPATH: a RUNPATH is not searched for libpng's own libz)
set(CMAKE_EXE_LINKER_FLAGS_INIT "$rpath")
set(CMAKE_SHARED_LINKER_FLAGS_INIT "$rpath")
EOF

dir=$root/$arch
if [ -n "${CROSS_REUSE:-}" ] && [ -f "$dir/CMakeCache.txt" ]; then
  echo "check-cross: $arch: reusing $dir (CROSS_REUSE)"
  [ -f "$dir/rg2.$arch" ] && mv -f "$dir/rg2.$arch" "$dir/rg2" # the wrapper's binary, back for make
else
rm -rf "$dir"
echo "check-cross: $arch configure"
PKG_CONFIG_LIBDIR=$libdir/pkgconfig:$sysroot/usr/share/pkgconfig PKG_CONFIG_SYSROOT_DIR=$sysroot \
  cmake -S "$src" -B "$dir" -DCMAKE_TOOLCHAIN_FILE="$tc" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DRG2_BUILD_TESTS=ON -DRG2_OCCT_TESTS=OFF -DRG2_BUILD_BENCH=OFF -DRG2_TEST_TIMEOUT="${CROSS_TIMEOUT:-1800}" "$@" >"$dir.cmake.log" 2>&1 ||
  { cat "$dir.cmake.log"; echo "check-cross: $arch: cmake failed" >&2; exit 1; }
fi
echo "check-cross: $arch build"
cmake --build "$dir" -j"$jobs" >"$dir.build.log" 2>&1 ||
  { grep -E "error|warning" "$dir.build.log" | head -40; echo "check-cross: $arch: build failed" >&2; exit 1; }
warnings=$(grep -c "warning:" "$dir.build.log" || true)
echo "check-cross: $arch: built, $warnings compiler warnings ($dir.build.log)"
built=$(date +%s)

# The CLI tests exec the rg2 binary themselves: without binfmt_misc, a wrapper runs it in qemu.
if ! "$dir/rg2" --version >/dev/null 2>&1; then
  mv "$dir/rg2" "$dir/rg2.$arch"
  printf '#!/bin/sh\nexec %s -L /usr/%s "%s" "$@"\n' "$qemu" "$triple" "$dir/rg2.$arch" >"$dir/rg2"
  chmod +x "$dir/rg2"
fi

# (and for any binary linked otherwise: qemu hands the guest this variable)
export QEMU_SET_ENV=LD_LIBRARY_PATH=$libdir:$sysroot/lib/$multi
# (each test's TIMEOUT, RG2_TEST_TIMEOUT, wins over ctest --timeout: set at configure time above)
echo "check-cross: $arch ctest (-j$jobs, timeout ${CROSS_TIMEOUT:-1800} s a test)"
rc=0
(cd "$dir" && ctest -j"$jobs" --timeout "${CROSS_TIMEOUT:-1800}" --output-on-failure \
  ${CROSS_TESTS:+-R "$CROSS_TESTS"} >"$dir.ctest.log" 2>&1) || rc=1
end=$(date +%s)
grep -E "tests passed|\(Failed\)|\(Timeout\)|\(SEGFAULT\)|\*\*\*" "$dir.ctest.log" | sed "s/^/check-cross: $arch: /"
echo "check-cross: $arch: build $((built - start)) s, tests $((end - built)) s ($dir.ctest.log)"
exit $rc
