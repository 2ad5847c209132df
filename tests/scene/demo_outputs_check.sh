#!/usr/bin/env bash
# adb-demo --scene with --out and --render writes what it says: steps.csv (a header and a row
# per step), summary.json, events.jsonl for an overlap scene, frames of the stated size and a
# strip; and a pile of a mesh file (--mesh) writes the same outputs for every backend of
# --compare, and the comparison picture.  demo_outputs_check.sh ADB_DEMO SCENES_DIR
set -euo pipefail
demo=$1
scenes=$2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$demo" --scene "$scenes/gears_contacts.json" --steps 6 --render --frames-every 2 \
  --width 200 --height 150 --out "$out/gears" > "$out/gears.log" 2>&1 || { cat "$out/gears.log"; exit 1; }
[ "$(wc -l < "$out/gears/steps.csv")" -eq 7 ] || { echo "FAIL: steps.csv rows"; exit 1; }
grep -q '"effects": "contacts"' "$out/gears/summary.json" || { echo "FAIL: summary.json"; exit 1; }
[ "$(ls "$out/gears/frames" | wc -l)" -eq 3 ] || { echo "FAIL: frames"; ls "$out/gears/frames"; exit 1; }
# PNG header: width and height, big-endian, at bytes 16 and 20.
size=$(od -An -tu1 -j16 -N8 "$out/gears/frames/00000.png" | tr -s ' ')
[ "$size" = " 0 0 0 200 0 0 0 150" ] || { echo "FAIL: frame size '$size'"; exit 1; }
[ -s "$out/gears/strip.png" ] || { echo "FAIL: strip.png"; exit 1; }
"$demo" --scene "$scenes/assembly_path.json" --backend exact --out "$out/path" > "$out/path.log" 2>&1 ||
  { cat "$out/path.log"; exit 1; }
[ "$(wc -l < "$out/path/events.jsonl")" -eq 2 ] || { echo "FAIL: events.jsonl"; cat "$out/path/events.jsonl"; exit 1; }
# A pile of any mesh file: a tetrahedron written here, rendered and compared.
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n' > "$out/tetra.obj"
"$demo" --mesh "$out/tetra.obj" --bodies 6 --steps 8 --render --compare --frames-every 4 \
  --width 160 --height 120 --probe-every 4 --out "$out/pile" > "$out/pile.log" 2>&1 ||
  { cat "$out/pile.log"; exit 1; }
for backend in adb exact gimpact; do
  [ "$(wc -l < "$out/pile/$backend/steps.csv")" -eq 9 ] || { echo "FAIL: pile $backend steps.csv"; exit 1; }
  grep -q '"dynamic_bodies": 6' "$out/pile/$backend/summary.json" || { echo "FAIL: pile $backend summary.json"; exit 1; }
  [ -s "$out/pile/$backend/strip.png" ] || { echo "FAIL: pile $backend strip.png"; exit 1; }
done
[ -s "$out/pile/comparison.png" ] || { echo "FAIL: pile comparison.png"; exit 1; }
echo "outputs written"
