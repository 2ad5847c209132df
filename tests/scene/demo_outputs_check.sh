#!/usr/bin/env bash
# adb-demo --scene with --out and --render writes what it says: steps.csv (a header and a row
# per step), summary.json, events.jsonl for an overlap scene, frames of the stated size and a
# strip.  demo_outputs_check.sh ADB_DEMO SCENES_DIR
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
echo "outputs written"
