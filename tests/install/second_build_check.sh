#!/usr/bin/env bash
# The second build a user may make, checked in one: the libraries shared
# (-DBUILD_SHARED_LIBS=ON) against Debian's double-precision Bullet (-DADB_BULLET_DOUBLE=ON).
# The plugin's tests pass against bullet-float64, and the package installs and links an
# application as check.sh does (CMake package and pkg-config, Bullet's flags coming from the
# package). One build for both, not two: each costs a build of the layers, and make test
# runs on 2 cores. The layers that do not include Bullet (core, io, support) compile with the
# first build's flags and come from ccache where it is installed.
#   second_build_check.sh SOURCE_DIR
set -euo pipefail
source=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake -S "$source" -B "$work/build" -DCMAKE_BUILD_TYPE=Release -DBUILD_SHARED_LIBS=ON \
  -DADB_BULLET_DOUBLE=ON -DADB_BUILD_DEMOS=OFF -DADB_BUILD_PYTHON=OFF > "$work/configure.log"
start=$SECONDS
cmake --build "$work/build" -j "$(nproc)" \
  --target adb_core adb_bullet adb_io adb_scene adb_support adb_bullet_tests \
  > "$work/build.log" 2>&1 || { tail -50 "$work/build.log"; exit 1; }
echo "built in $((SECONDS - start)) s"
grep -q 'ADB_BULLET_DOUBLE_PRECISION 1' "$work/build/plugin/bullet/include/adb/bullet/config.h" ||
  { echo "FAIL: the second build is not double precision"; exit 1; }
for lib in adb_core adb_bullet adb_io adb_scene adb_support; do
  [ -f "$work/build/plugin/${lib#adb_}/lib$lib.so" ] || { echo "FAIL: lib$lib.so not built"; exit 1; }
done
"$work/build/bin/adb_bullet_tests" --gtest_brief=1
bash "$source/tests/install/check.sh" "$work/build" "$source"
