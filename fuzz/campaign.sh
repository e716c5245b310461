#!/usr/bin/env bash
# Runs every fuzz target (or the ones named) for SECONDS each, JOBS targets at a
# time, and prints one line per target: executions, new corpus files, and the
# crashes, out-of-memory inputs (over 1 GiB RSS) and timeouts (over 2 s for one
# input) it saved under fuzz/artifacts/<target>/.
#   fuzz/campaign.sh [SECONDS] [JOBS] [TARGET...]     # defaults: 600 s, 1 job, all
# Seeds the corpus first when it is missing (fuzz/seed.sh). Logs: fuzz/logs/.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
cd "$here"
secs="${1:-600}"
jobs="${2:-1}"
shift $(( $# > 2 ? 2 : $# ))
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
    mapfile -t targets < <(cargo +nightly fuzz list)
fi
[ -d corpus ] || ./seed.sh
mkdir -p logs
cargo +nightly fuzz build -O >logs/build.log 2>&1 || { tail -20 logs/build.log; exit 1; }
bin="$here/target/x86_64-unknown-linux-gnu/release"
count() { ls "artifacts/$1" | grep -c "^$2-" || true; }
run_one() {
    local t="$1" k
    mkdir -p "artifacts/$t" "corpus/$t"
    local -A before
    for k in crash oom timeout; do before[$k]="$(count "$t" "$k")"; done
    local files_before
    files_before="$(ls "corpus/$t" | wc -l)"
    # Exit status is non-zero on a finding; the line below reports it.
    "$bin/$t" "corpus/$t" -max_total_time="$secs" -rss_limit_mb=1024 -timeout=2 \
        -artifact_prefix="artifacts/$t/" -print_final_stats=1 >"logs/$t.log" 2>&1 || true
    local execs secs_run
    execs="$(grep -o 'stat::number_of_executed_units: *[0-9]*' "logs/$t.log" | grep -o '[0-9]*$' || echo '?')"
    secs_run="$(grep -o 'Done [0-9]* runs in [0-9]* second' "logs/$t.log" | grep -o 'in [0-9]*' | grep -o '[0-9]*' || echo '?')"
    local files
    files="$(ls "corpus/$t" | wc -l)"
    printf '%-14s %5s s %12s execs %7s corpus files (+%s) %3s crashes %3s ooms %3s timeouts\n' \
        "$t" "$secs_run" "$execs" "$files" "$(( files - files_before ))" \
        "$(( $(count "$t" crash) - before[crash] ))" "$(( $(count "$t" oom) - before[oom] ))" \
        "$(( $(count "$t" timeout) - before[timeout] ))"
}
export -f run_one count
export secs bin
printf '%s\n' "${targets[@]}" | xargs -P "$jobs" -I{} bash -c 'run_one {}'
