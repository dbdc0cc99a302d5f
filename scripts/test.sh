#!/usr/bin/env bash
# The whole test suite: installs what is missing, configures, builds (sanitizers on) and runs CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
jobs=$(nproc 2>/dev/null || echo 2)
cmake --preset host-asan
cmake --build --preset host-asan -j "$jobs"
# A failed test is run once more: the HIL fault tests over pseudo-terminals can flake under load
# (see issue notes); a real failure fails twice.
ctest --preset host-asan -j "$jobs" --repeat until-pass:2
