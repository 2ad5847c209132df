#!/usr/bin/env bash
# -DBUILD_SHARED_LIBS=ON works: builds the libraries shared (no tests, no demos), then installs
# them and builds and runs the application against them as check.sh does (CMake package and
# pkg-config).
#   shared_check.sh SOURCE_DIR
set -euo pipefail
source=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake -S "$source" -B "$work/build" -DCMAKE_BUILD_TYPE=Release -DBUILD_SHARED_LIBS=ON \
  -DADB_BUILD_TESTS=OFF -DADB_BUILD_DEMOS=OFF -DADB_BUILD_PYTHON=OFF > "$work/configure.log"
cmake --build "$work/build" -j "$(nproc)" > "$work/build.log" 2>&1 ||
  { tail -50 "$work/build.log"; exit 1; }
for lib in adb_core adb_bullet adb_io; do
  [ -f "$work/build/plugin/${lib#adb_}/lib$lib.so" ] || { echo "FAIL: lib$lib.so not built"; exit 1; }
done
bash "$source/tests/install/check.sh" "$work/build" "$source"
