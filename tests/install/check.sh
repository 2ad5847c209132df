#!/usr/bin/env bash
# Installs the built project into a fresh prefix and builds an application against it, as a
# user would: through the installed CMake package (find_package(adb CONFIG REQUIRED)), and
# through pkg-config (adb.pc; --static when the libraries are static).
#   check.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1
source=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
# The installed core carries only what a collision user needs: the generated geometry and
# benchmark poses are adb::support's.
for gone in mesh_generators.h benchmark_poses.h; do
  if [ -e "$work/prefix/include/adb/core/$gone" ]; then echo "FAIL: adb/core/$gone installed"; exit 1; fi
  [ -e "$work/prefix/include/adb/support/$gone" ] || { echo "FAIL: adb/support/$gone missing"; exit 1; }
done
cmake -S "$source/tests/install/consumer" -B "$work/consumer" \
  -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_BUILD_TYPE=Release > "$work/configure.log"
cmake --build "$work/consumer" > "$work/build.log"
"$work/consumer/consumer" "$work"

# The same application through pkg-config, with no CMake.
pc=$(dirname "$(find "$work/prefix" -name adb.pc | head -1)")
[ -n "$pc" ] || { echo "FAIL: no adb.pc installed"; exit 1; }
static=""
if [ -n "$(find "$work/prefix" -name libadb_core.a)" ]; then static="--static"; fi
export PKG_CONFIG_PATH="$pc${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}"
# shellcheck disable=SC2046  # pkg-config's flags are meant to split
"${CXX:-c++}" -std=c++17 -O1 "$source/tests/install/consumer/main.cpp" -o "$work/consumer-pc" \
  $(pkg-config --cflags adb) $(pkg-config $static --libs adb) > "$work/pc-build.log" 2>&1 ||
  { cat "$work/pc-build.log"; echo "FAIL: pkg-config build"; exit 1; }
LD_LIBRARY_PATH="$(dirname "$(find "$work/prefix" -name 'libadb_core*' | head -1)")${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" \
  "$work/consumer-pc" "$work"
echo "pkg-config consumer ran ($static)"
