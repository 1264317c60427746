#!/bin/bash
# Runs each libFuzzer target of BUILD (default build-fuzz) for SECONDS (default 900), seeded with
# the corpus (tests/corpus, tests/data, fuzz/corpus/<target>), then merges what added coverage
# into fuzz/corpus/<target>, which `make test` replays. A crash or a leak ends a target's run; it,
# an input past the time limit or one past the memory limit leaves its input in BUILD/findings/
# and the script's exit status 1. One line per target
# goes to standard output: executions, their rate, coverage, corpus size and findings.
#
#   fuzz/run.sh [BUILD] [SECONDS] [TARGET...]
set -u
build=${1:-build-fuzz}
seconds=${2:-900}
shift $(($# < 2 ? $# : 2))
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(scene obj bvh checkpoint ply)
here=$(cd "$(dirname "$0")/.." && pwd)
status=0
for target in "${targets[@]}"; do
  program="$build/fuzz/vdcloth_fuzz_$target"
  work="$build/fuzz-corpus/$target"
  findings="$build/findings"
  mkdir -p "$work" "$findings" "$here/fuzz/corpus/$target"
  log="$build/fuzz-$target.log"
  # -timeout: a scene may build a large procedural mesh or body, seconds of honest work.
  # -max_len: new inputs stay small (the checkpoint seeds are 1.3 and 1.6 kB), and so does the saved corpus;
  # larger seeds are cut to it (the corpus test runs them whole).
  max_len=4096
  [ "$target" = checkpoint ] && max_len=16384
  # Fork mode: an input that runs out of time or memory (a scene may honestly ask for a 4-million-
  # face grid, seconds of work in Release and minutes under the sanitizers) is kept as a finding
  # and fuzzing goes on; a crash ends the run.
  started=$SECONDS
  stamp="$build/fuzz-$target.started"
  touch "$stamp"
  "$program" -fork=1 -ignore_timeouts=1 -ignore_ooms=1 -max_total_time="$seconds" -max_len=$max_len -timeout=60 -rss_limit_mb=4096 \
    -artifact_prefix="$findings/$target-" "$work" "$here/fuzz/corpus/$target" "$here/tests/corpus" "$here/tests/data" >"$log" 2>&1
  code=$?
  elapsed=$((SECONDS - started))
  runs=$(grep -o '^#[0-9]*' "$log" | tail -1 | tr -d '#')
  rate=$(grep -o 'exec/s:\? [0-9]*' "$log" | tail -1 | grep -o '[0-9]*$')
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1)
  found=$(find "$findings" -name "$target-*" -newer "$stamp" | wc -l)  # this run's only
  timeouts=$(grep -o 'oom/timeout/crash: [0-9]*/[0-9]*/[0-9]*' "$log" | tail -1 | cut -d' ' -f2)
  "$program" -merge=1 -max_len=$max_len "$here/fuzz/corpus/$target" "$work" >"$build/fuzz-$target-merge.log" 2>&1
  saved=$(ls "$here/fuzz/corpus/$target" | wc -l)
  echo "$target: ${elapsed} s, ${runs:-?} executions (${rate:-?}/s), ${cov:-cov: ?}, exit $code, oom/timeout/crash ${timeouts:-0/0/0}, $found finding(s), $saved inputs saved in fuzz/corpus/$target"
  [ "$code" -ne 0 ] || [ "$found" -ne 0 ] && status=1
done
exit $status
