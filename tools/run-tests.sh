#!/usr/bin/env bash
# Builds cacao twice (release, and ASan+UBSan) and runs the whole ctest suite in both; then a
# ThreadSanitizer build of the multi-threaded test alone.
# Tests that need ../shared (scenes, AMD reference) report "skipped" where it is absent;
# point CACAO_SHARED_DIR elsewhere with: CACAO_SHARED_DIR=/path tools/run-tests.sh
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
shared=${CACAO_SHARED_DIR:-$(pwd)/../shared}
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DCACAO_SHARED_DIR="$shared"
cmake --build build -j "$jobs"
ctest --test-dir build --output-on-failure -j "$jobs"
cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCACAO_SANITIZE=ON -DCACAO_SHARED_DIR="$shared"
cmake --build build-sanitize -j "$jobs"
ctest --test-dir build-sanitize --output-on-failure -j "$jobs"
# ThreadSanitizer: only the test that runs contexts on several threads (seconds to build and run).
cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCACAO_SANITIZE_THREAD=ON -DCACAO_SHARED_DIR="$shared"
cmake --build build-tsan -j "$jobs" --target test_two_threads
ctest --test-dir build-tsan --output-on-failure -R '^two_threads$'
