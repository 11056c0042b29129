#!/usr/bin/env bash
# Set-up (Debian packages, configure, build), then the main job.
set -euo pipefail
cd "$(dirname "$0")"
# The CLI, its man pages (cmake --install installs them) and the Python module (docs/python.md): what the docs' next
# steps use; ./test.sh builds the tests and benchmarks too.
scripts/setup.sh crankcheck crankcheck_man_pages crankcheck_python_module
# The main job: the default validation campaign; the report goes to out/report/ (index.md, index.html).
build/bin/crankcheck validate --out out/report "$@"
