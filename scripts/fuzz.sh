#!/usr/bin/env bash
# Bounded libFuzzer run of the scene parser (fuzz/scene_fuzzer.cc) on a seed corpus of the example scenes.
#   scripts/fuzz.sh [SECONDS]      (default 60)
# A crash leaves its input in build-fuzz/artifacts/; add it to tests/scene/fuzz_regressions/ with the fix.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
scripts/setup.sh
for p in clang-14 libclang-rt-14-dev; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    sudo=""; if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends clang-14 libclang-rt-14-dev >/dev/null
  fi
done
if [ ! -f build-fuzz/CMakeCache.txt ]; then
  cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++-14 >/dev/null
fi
cmake --build build-fuzz -j"$(nproc)" --target scene_fuzzer >build-fuzz/build.log 2>&1 || {
  tail -n 40 build-fuzz/build.log >&2; echo "fuzz: build failed" >&2; exit 1; }
corpus=$(mktemp -d)
trap 'rm -rf "$corpus"' EXIT
cp scenes/*.toml tests/scene/fuzz_regressions/* "$corpus"/ 2>/dev/null || true
mkdir -p build-fuzz/artifacts
build-fuzz/bin/scene_fuzzer "$corpus" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
  -artifact_prefix=build-fuzz/artifacts/ -print_final_stats=1 2>build-fuzz/fuzz.log || {
  tail -n 40 build-fuzz/fuzz.log >&2; echo "fuzz: a crash; its input is in build-fuzz/artifacts/" >&2; exit 1; }
grep -E "stat::number_of_executed_units|Done" build-fuzz/fuzz.log | tail -2
echo "fuzz: no crash in ${seconds} s"
