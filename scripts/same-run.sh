#!/usr/bin/env bash
# Whether two runs of one scene are the same run bit for bit but for their timings:
# scripts/same-run.sh RUN_A RUN_B. Compares stats.csv without its timing and memory columns
# (those named *seconds*, resident_mib), every file under frames/ byte for byte, log.txt, and
# summary.json without its timings, memory, machine and finishing time. Exits 0 when they are
# the same, 1 with the first differences otherwise.
set -euo pipefail
if [ $# -ne 2 ]; then echo "usage: scripts/same-run.sh RUN_A RUN_B" >&2; exit 2; fi
a=$1 b=$2
status=0
untimed_stats() {
  awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) keep[i] = ($i !~ /seconds/ && $i != "resident_mib") }
           { line = ""; for (i = 1; i <= NF; ++i) if (keep[i]) line = line (line == "" ? "" : ",") $i; print line }' "$1"
}
untimed_summary() {
  grep -v -E '"(cpu_seconds|finished|peak_memory_kib|total_seconds|steal|max|mean|cores|cpu|host|rebuild_seconds_per_face|seconds_a_frame|move_seconds)"' "$1" |
    grep -v -E '^\s*[0-9.e+-]+,?$'
}
if ! diff <(untimed_stats "$a/stats.csv") <(untimed_stats "$b/stats.csv") > /tmp/same-run.$$ ; then
  echo "stats.csv differs:"; head -5 /tmp/same-run.$$; status=1
fi
if ! diff <(untimed_summary "$a/summary.json") <(untimed_summary "$b/summary.json") > /tmp/same-run.$$ ; then
  echo "summary.json differs:"; head -10 /tmp/same-run.$$; status=1
fi
if [ -f "$a/log.txt" ] || [ -f "$b/log.txt" ]; then
  if ! diff -q "$a/log.txt" "$b/log.txt" > /dev/null; then echo "log.txt differs"; status=1; fi
fi
if ! diff -rq "$a/frames" "$b/frames" > /tmp/same-run.$$; then
  echo "frames differ:"; head -5 /tmp/same-run.$$; status=1
fi
rm -f /tmp/same-run.$$
n=$(ls "$a/frames" | wc -l)
[ $status -eq 0 ] && echo "same run: $(($(wc -l < "$a/stats.csv") - 1)) frames, $n frame files"
exit $status
