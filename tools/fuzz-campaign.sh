#!/usr/bin/env bash
# Long fuzzing campaigns of the libFuzzer harnesses (tests/fuzz/), built by the sanitizer build.
#   tools/fuzz-campaign.sh [SECONDS_PER_HARNESS] [HARNESS...]   (default 600 s, every harness)
# Each harness starts from its seed corpus plus what earlier campaigns found (build-sanitize/
# tests/fuzz/found/NAME), runs single-process for the given time, and any crash input is kept in
# build-sanitize/tests/fuzz/crashes/. One line per harness goes to stdout and to
# build-sanitize/tests/fuzz/campaign.txt: name, seconds, executions, corpus size, result.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-600}
shift || true
harnesses=("$@")
[ ${#harnesses[@]} -gt 0 ] || harnesses=(pfm png exr camera_json settings_json cli_args bench_json inspect_args inspect_costs)
build=build-sanitize/tests/fuzz
if [ ! -x "$build/fuzz_pfm" ]; then
    cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCACAO_SANITIZE=ON
    cmake --build build-sanitize -j "$(nproc)"
fi
mkdir -p "$build/crashes"
for name in "${harnesses[@]}"; do
    mkdir -p "$build/found/$name"
    log="$build/campaign-$name.log"
    status=clean
    "$build/fuzz_$name" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 \
        -artifact_prefix="$build/crashes/$name-" "$build/found/$name" "tests/fuzz/corpus/$name" >"$log" 2>&1 ||
        status="FOUND (see $log and $build/crashes/)"
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
    units=$(find "$build/found/$name" -type f | wc -l)
    echo "$name seconds=$seconds executions=${execs:-?} found_corpus=$units result=$status" | tee -a "$build/campaign.txt"
done
