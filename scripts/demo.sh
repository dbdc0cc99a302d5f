#!/usr/bin/env bash
# The main job: installs what is missing, builds build/bin/curvestep and runs its demo.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
jobs=$(nproc 2>/dev/null || echo 2)
cmake --preset host-release
cmake --build --preset host-release -j "$jobs" --target curvestep
build/bin/curvestep demo --out build/demo "$@"
