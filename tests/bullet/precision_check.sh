#!/usr/bin/env bash
# A translation unit that includes adb::bullet's headers with the other precision than the
# library was built for fails to compile, saying why. (The plugin's tests against
# bullet-float64: tests/install/second_build_check.sh.)
#   precision_check.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
source=$1
build=$2
cxx=${CXX:-c++}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
includes=(-I"$source/plugin/core/include" -I"$source/plugin/bullet/include"
          -I"$build/plugin/bullet/include" -isystem /usr/include/eigen3 -isystem /usr/include/bullet)
printf '#include "adb/bullet/mesh_shape.h"\nint main() { return 0; }\n' > "$work/tu.cpp"

# This build's precision, read from its generated config.
if grep -q 'ADB_BULLET_DOUBLE_PRECISION 1' "$build/plugin/bullet/include/adb/bullet/config.h"; then
  other=()  # the library is double: a single-precision unit must fail
else
  other=(-DBT_USE_DOUBLE_PRECISION)
fi
if "$cxx" -std=c++17 -fsyntax-only "${other[@]}" "${includes[@]}" "$work/tu.cpp" 2> "$work/err.txt"; then
  echo "FAIL: a unit at the other precision compiled against this build's headers"
  exit 1
fi
grep -q "another precision" "$work/err.txt" || { cat "$work/err.txt"; exit 1; }
echo "mismatch refused at compile time"
