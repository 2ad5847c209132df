#!/usr/bin/env bash
# Renders the gallery's pictures (docs/gallery/NAME.png: three frames of each scene side by
# side, at the steps that show what the scene is about) with build/bin/adb-demo.
#   demos/scenes/gallery.sh [OUT_DIR]   (default: build/gallery; the PNGs are copied to docs/)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
out=${1:-$root/build/gallery}
demo=$root/build/bin/adb-demo
declare -A strip=(
  [pile]=30,120,360
  [gears_contacts]=30,40,48
  [gears_dynamics]=60,180,360
  [assembly_path]=60,105,285
  [stack]=2,240,480
  [fast_ball_wall]=2,4,60
)
for scene in "${!strip[@]}"; do
  "$demo" --scene "$root/demos/scenes/$scene.json" --render --width 480 --height 360 \
    --strip-steps "${strip[$scene]}" --out "$out/$scene" > "$out-$scene.log" 2>&1 ||
    { cat "$out-$scene.log"; exit 1; }
  cp "$out/$scene/strip.png" "$root/docs/gallery/$scene.png"
  echo "$scene: docs/gallery/$scene.png"
done
