#!/usr/bin/env bash
# make fuzz: runs every libFuzzer target (preset fuzz, build-fuzz/bin/fuzz-*) for SECONDS each
# on a working copy of its checked-in corpus, and prints executions and findings per target.
# New inputs that cover more stay in build-fuzz/corpus/TARGET; crashes, leaks and timeouts go
# to build-fuzz/findings/TARGET/ (add a fixed one to tests/fuzz/corpus/TARGET/ as a regression).
#   tests/fuzz/run_fuzz.sh [SECONDS] [TARGET...]
# FUZZ_RUNS=N stops a target after N executions instead (SECONDS still caps it).
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
seconds=${1:-60}
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(mesh_obj mesh_stl mesh_ply mesh_off mesh_gltf mesh_3mf tree_query scene_file)
fi
status=0
# A target that exits 0 found nothing. mesh_gltf and mesh_3mf read through assimp in a forked
# child (the isolated reader applications get): a crash there is a MeshFileError. The child
# drops the crash handlers it inherits, but a memory error that ASan catches in it still makes
# libFuzzer's death callback write a crash-* file. Those are counted as "contained" and
# removed, not reported as findings.
printf '%-12s %12s %10s %9s %s\n' target executions exec/s contained findings
for t in "${targets[@]}"; do
  corpus=$root/build-fuzz/corpus/$t
  findings=$root/build-fuzz/findings/$t
  mkdir -p "$corpus" "$findings"
  cp -n "$root/tests/fuzz/corpus/$t"/* "$corpus/" 2>/dev/null
  log=$root/build-fuzz/fuzz-$t.log
  # assimp leaks a few hundred bytes on some damaged files (inside libassimp, which we cannot
  # mend); its targets fuzz for crashes, hangs and memory errors, not leaks. adb's own readers
  # (PLY, OFF) and the other targets keep leak detection.
  # OBJ and STL read in the fuzzer's process, where those leaks add up (about 1 KB per damaged
  # STL): their RSS limit is 4 GB, and LeakSanitizer's check at exit is off too.
  extra=()
  leaks=1
  rss=2048
  case $t in
    mesh_obj|mesh_stl) extra=(-detect_leaks=0); leaks=0; rss=4096 ;;
    mesh_gltf|mesh_3mf) extra=(-detect_leaks=0); leaks=0 ;;
  esac
  # A fork copies the parent's page tables and the child's exit tears them down: with ASan's
  # 256 MB quarantine of freed memory, that was most of the isolated targets' time.
  quarantine=
  case $t in mesh_gltf|mesh_3mf) quarantine=:quarantine_size_mb=16 ;; esac
  # -timeout: an input slower than 10 s is a finding (a hang); -rss_limit_mb: so is more memory.
  [ -n "${FUZZ_RUNS:-}" ] && extra+=(-runs="$FUZZ_RUNS")
  stamp=$(mktemp)  # artifacts newer than this are this run's
  ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=$leaks$quarantine \
    "$root/build-fuzz/bin/fuzz-$t" "$corpus" -max_total_time="$seconds" -timeout=10 \
    -rss_limit_mb=$rss -artifact_prefix="$findings/" -print_final_stats=1 "${extra[@]}" > "$log" 2>&1
  code=$?
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | tail -1 | grep -o '[0-9]*$')
  rate=$(grep -o 'stat::average_exec_per_sec: *[0-9]*' "$log" | tail -1 | grep -o '[0-9]*$')
  artifacts=$(find "$findings" -type f -newer "$stamp" | wc -l)
  if [ $code -eq 0 ]; then
    find "$findings" -type f -newer "$stamp" -delete
    printf '%-12s %12s %10s %9s %s\n' "$t" "${execs:-?}" "${rate:-?}" "$artifacts" 0
  else
    status=1
    printf '%-12s %12s %10s %9s %s\n' "$t" "${execs:-?}" "${rate:-?}" "?" 1
    echo "  $t: exit $code, see $log and $findings"
  fi
  rm -f "$stamp"
done
exit $status
