#!/usr/bin/env bash
# Set-up (Debian packages, configure, build), then the main job.
set -euo pipefail
cd "$(dirname "$0")"
scripts/setup.sh
build/bin/crankcheck eval scenes/single_cylinder.toml --engine both --phi-deg 0,37.5,90,180,270
