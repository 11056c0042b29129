#!/usr/bin/env bash
# Set-up (Debian packages, configure, build), then the main job.
set -euo pipefail
cd "$(dirname "$0")"
scripts/setup.sh crankcheck  # the CLI alone: ./test.sh builds the tests and benchmarks
# The main job: the default validation campaign; the report goes to out/report/ (index.md, index.html).
build/bin/crankcheck validate --out out/report "$@"
