#!/usr/bin/env bash
# Set-up (Debian packages, configure, build), then every test under ctest.
set -euo pipefail
cd "$(dirname "$0")"
scripts/setup.sh
ctest --test-dir build --output-on-failure -j"$(nproc)"
