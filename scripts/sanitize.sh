#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer build (build-asan/) and a run of the analytic, scene and MuJoCo unit
# tests, the CLI tests, the output-safety tests and a small sweep of the gate (Simbody and MuJoCo) under it. Called by .ci/run after ./test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
if [ ! -f build-asan/CMakeCache.txt ]; then
  cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCRANKCHECK_SANITIZE=ON >/dev/null
fi
if ! cmake --build build-asan -j"$(nproc)" --target analytic_test scene_test mujoco_model_test gate_test cli_test validate_test crankcheck \
    >build-asan/build.log 2>&1; then
  tail -n 60 build-asan/build.log >&2
  echo "sanitize: build failed (build-asan/build.log)" >&2
  exit 1
fi
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
# Leaks of third-party libraries on their error paths, each explained in the file.
export LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
build-asan/bin/analytic_test --gtest_brief=1
build-asan/bin/scene_test --gtest_brief=1
build-asan/bin/mujoco_model_test --gtest_brief=1
build-asan/bin/cli_test --gtest_brief=1
# The output-folder rule, failed writes and signals (issue 10) under the sanitizers; the odd-path runs of the full
# quick campaign stay in ./test.sh.
build-asan/bin/validate_test --gtest_brief=1 --gtest_filter='OutputSafetyTest.*:Signals/*'
# A small sweep: every quantity for k = 1, 2, 4 and 12, both strokes, all lambdas and gammas, by Simbody and MuJoCo
# (the three-way gate is in the same pass), plus the reduced model and the paper's verdicts.
build-asan/bin/gate_test --gtest_brief=1 \
  --gtest_filter='Gate/LayoutGateTest.*:Gate/BalanceGateTest.*:Gate/CrossCheckTest.*/k1_*:Gate/CrossCheckTest.*/k2_*:Gate/CrossCheckTest.*/k4_*:Gate/CrossCheckTest.*/k12_*:Gate/ReducedModelTest.*/k3_*:Gate/PaperAsPrinted*:PaperAsPrinted.*:CrossCheckScenes.*:ThreeWayScenes.*:TorsionGate.*:Trains/TorsionSteadyGateTest.*/0'
echo "sanitize: 0 errors (ASan + UBSan)"
