#!/usr/bin/env bash
# Shared set-up of ./run.sh and ./test.sh: installs the Debian packages the project needs (only the missing
# ones), configures (once) and builds into build/. Idempotent: a second run only rebuilds what changed.
#   scripts/setup.sh [TARGET...]   build only these targets (./run.sh: the CLI, so the first report comes before the
#                                  tests are built); none: everything (./test.sh)
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(g++ cmake make pkg-config libeigen3-dev libboost-dev libsimbody-dev libcli11-dev libtomlplusplus-dev munge slurm-client
          nlohmann-json3-dev libgtest-dev libgmock-dev libbenchmark-dev gnuplot-nox libhwy-dev libsleef-dev
          libcmark-gfm-dev libcmark-gfm-extensions-dev python3 chromium python3-jsonschema parallel slurmctld slurmd
          libmujoco-dev libqhull-dev  # libqhull-dev: the include folder Debian's mujoco::mujoco target names
          libode-dev  # ODE 0.16 (ode_models/)
          libbullet-dev  # Bullet 3.24, its double-precision build (bullet_models/)
          libbox2d-dev  # Box2D 2.4, single precision (box2d_models/)
          python3-dev pybind11-dev python3-numpy python3-pytest  # the Python module (python/) and its tests
          python3-mpmath)  # the high-precision reference of tests/python/test_angles.py
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

if [ ! -f build/CMakeCache.txt ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
fi

# make's "[ NN%]" lines of the build on stdin, shown on stderr as one updated line with the elapsed time (a terminal)
# or a line every 10 % (a log, e.g. CI).
show_progress() {
  local line pct=0 shown=-10 start=$SECONDS
  while IFS= read -r line; do
    [[ $line =~ ^\[\ *([0-9]+)%\] ]] || continue
    ((BASH_REMATCH[1] > pct)) && pct=${BASH_REMATCH[1]}
    local t=$((SECONDS - start))
    if [ -t 2 ]; then
      printf '\rsetup: building %3d%%, %dm%02ds' "$pct" $((t / 60)) $((t % 60)) >&2
    elif ((pct >= shown + 10)); then
      shown=$((pct / 10 * 10))
      printf 'setup: building %3d%%, %dm%02ds\n' "$pct" $((t / 60)) $((t % 60)) >&2
    fi
  done
  if [ -t 2 ]; then printf '\n' >&2; fi
}

# The first build (of the CLI for ./run.sh, of everything for ./test.sh: its program or the gate's tests not there
# yet) takes minutes: its progress is shown. A rebuild stays quiet. Both go to build/build.log in full.
status=0
targets=()
# A target the configure did not make is left out, with a word: the Python module's without pybind11, Python's headers
# or NumPy, or with -DCRANKCHECK_PYTHON=OFF.
known=$(cmake --build build --target help 2>/dev/null || true)
for target in "$@"; do
  if grep -qx "\.\.\. $target" <<<"$known"; then
    targets+=(--target "$target")
  else
    echo "setup: no target $target in this configuration (see build/CMakeCache.txt); not built" >&2
  fi
done
first=build/bin/gate_test
((${#targets[@]})) && first=build/bin/crankcheck
if [ ! -x "$first" ]; then
  echo "setup: first build, several minutes on 2 cores (full output: build/build.log)" >&2
  cmake --build build -j"$(nproc)" "${targets[@]}" 2>&1 | tee build/build.log | show_progress || status=$?
else
  cmake --build build -j"$(nproc)" "${targets[@]}" >build/build.log 2>&1 || status=$?
fi
if ((status != 0)); then
  tail -n 60 build/build.log >&2
  echo "setup: build failed (full log: build/build.log)" >&2
  exit 1
fi
