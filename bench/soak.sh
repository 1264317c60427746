#!/bin/bash
# Long runs: karate and solo-dancer in view mode and sheet-fold adaptive, 1,000 frames each (the
# motions and cameras hold their last pose after their end). For each run: its exit status, the
# crossings at every 10th frame end (`vdcloth check` on meshes written every 10th frame), the
# resident memory at frames 100, 250, 500, 750 and the end (stats.csv's resident_mib), the peak
# at frame 100 and at the end (VmHWM sampled from /proc each second), and the counts of the
# recoveries stats.csv records. Not part of `make test`: an hour of CPU.
#
#   bench/soak.sh [VDCLOTH] [OUT_DIR] [FRAMES]    defaults: build/vdcloth out/soak 1000
set -u
vdcloth=${1:-build/vdcloth}
out=${2:-out/soak}
frames=${3:-1000}
here=$(cd "$(dirname "$0")/.." && pwd)  # the source tree

# The value of stats.csv column $2 at frame $3.
column_at() {
  awk -F, -v name="$2" -v frame="$3" 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == name) c = i; next } c && $1 == frame { print $c }' "$1"
}

# The sum of a stats.csv column named $2.
column_sum() {
  awk -F, -v name="$2" 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == name) c = i; next } c { s += $c } END { print s + 0 }' "$1"
}

# A value in kB from /proc/PID/status: $2 is VmHWM, the peak resident memory.
status_kb() {
  awk -v key="$2:" '$1 == key { print $2 }' "/proc/$1/status" 2>/dev/null
}

soak() {
  local name=$1 mode=$2
  local dir="$out/$name-$mode"
  rm -rf "$dir"
  mkdir -p "$dir"
  local started=$SECONDS
  "$vdcloth" run "$here/scenes/$name.json" --mode "$mode" --frames "$frames" --mesh-every 10 \
    --checkpoint-every 100 --out "$dir" >"$dir/run.log" 2>&1 &
  local pid=$!
  local hwm_100="" hwm_last="" done_frames=0
  while kill -0 "$pid" 2>/dev/null; do
    local hwm
    hwm=$(status_kb "$pid" VmHWM)
    if [ -n "$hwm" ]; then hwm_last=$hwm; fi
    if [ -f "$dir/stats.csv" ]; then done_frames=$(($(wc -l <"$dir/stats.csv") - 1)); fi
    if [ -z "$hwm_100" ] && [ "$done_frames" -ge 100 ] && [ -n "$hwm" ]; then hwm_100=$hwm; fi
    sleep 1
  done
  wait "$pid"
  local status=$?
  local seconds=$((SECONDS - started))
  "$vdcloth" check "$dir" >"$dir/check.log" 2>&1
  local check_status=$?
  local checked
  checked=$(awk '{ printf "%d checked, %d crossing", $1, $2 }' "$dir/check_status.txt" 2>/dev/null)
  local stats="$dir/stats.csv"
  local resident="" f
  for f in 100 250 500 750 "$frames"; do resident="$resident${resident:+ / }$(column_at "$stats" resident_mib "$f")"; done
  printf '| %s | %s | %d | %d | %d s | %s | %s | %s | %s / %s MiB | %d | %d | %d | %d |\n' \
    "$name" "$mode" "$status" "$(($(wc -l <"$stats") - 1))" "$seconds" "$check_status" "$checked" \
    "$resident" "$((${hwm_100:-0} / 1024))" "$((${hwm_last:-0} / 1024))" \
    "$(column_sum "$stats" halvings)" "$(column_sum "$stats" velocity_clamps)" \
    "$(column_sum "$stats" collision_fallbacks)" "$(column_sum "$stats" remesh_undone)"
}

echo "| scene | mode | exit | frames | wall | check exit | frames checked | resident MiB at 100 / 250 / 500 / 750 / end | peak at 100 / end | halvings | velocity clamps | collision fallbacks | remeshes undone |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
soak karate view
soak solo-dancer view
soak sheet-fold adaptive
