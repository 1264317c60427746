#!/bin/bash
# Long runs: karate and solo-dancer in view mode and sheet-fold adaptive, 1,000 frames each (the
# motions and cameras hold their last pose after their end). For each run: its exit status, the
# crossings at every 10th frame end (`vdcloth check --every 1` on meshes written every 10th frame),
# resident memory at frames 100 and 1,000 (peak and current, sampled from /proc each second), and
# the counts of the recoveries stats.csv records. Not part of `make test`: an hour of CPU.
#
#   bench/soak.sh [VDCLOTH] [OUT_DIR] [FRAMES]    defaults: build/vdcloth out/soak 1000
set -u
vdcloth=${1:-build/vdcloth}
out=${2:-out/soak}
frames=${3:-1000}
here=$(cd "$(dirname "$0")/.." && pwd)

# The sum of a stats.csv column named $2.
column_sum() {
  awk -F, -v name="$2" 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == name) c = i; next } c { s += $c } END { print s + 0 }' "$1"
}

# A value in kB from /proc/PID/status: $2 is VmRSS or VmHWM.
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
  local rss_100="" hwm_100="" rss_last="" hwm_last="" done_frames=0
  while kill -0 "$pid" 2>/dev/null; do
    local rss hwm
    rss=$(status_kb "$pid" VmRSS)
    hwm=$(status_kb "$pid" VmHWM)
    if [ -n "$rss" ]; then rss_last=$rss; hwm_last=$hwm; fi
    if [ -f "$dir/stats.csv" ]; then done_frames=$(($(wc -l <"$dir/stats.csv") - 1)); fi
    if [ -z "$hwm_100" ] && [ "$done_frames" -ge 100 ] && [ -n "$rss" ]; then rss_100=$rss; hwm_100=$hwm; fi
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
  printf '| %s | %s | %d | %d | %d s | %s | %s | %s / %s MiB | %s / %s MiB | %d | %d | %d | %d |\n' \
    "$name" "$mode" "$status" "$(($(wc -l <"$stats") - 1))" "$seconds" "$check_status" "$checked" \
    "$((${hwm_100:-0} / 1024))" "$((${rss_100:-0} / 1024))" "$((${hwm_last:-0} / 1024))" "$((${rss_last:-0} / 1024))" \
    "$(column_sum "$stats" halvings)" "$(column_sum "$stats" velocity_clamps)" \
    "$(column_sum "$stats" collision_fallbacks)" "$(column_sum "$stats" remesh_undone)"
}

echo "| scene | mode | exit | frames | wall | check exit | frames checked | peak / current RSS at 100 | peak / current RSS at end | halvings | velocity clamps | collision fallbacks | remeshes undone |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
soak karate view
soak solo-dancer view
soak sheet-fold adaptive
