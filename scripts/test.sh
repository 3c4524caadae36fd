#!/usr/bin/env bash
# The README's test command: installs what is missing, builds, runs every test
# through ctest (MPI tests run under `mpirun -np 2` from ctest).
# Usage: scripts/test.sh [release|asan]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
flavour="${1:-release}"
"$root/scripts/install_deps.sh"
"$root/scripts/build.sh" "$flavour"
cd "$root/build/$flavour"
ctest --output-on-failure --parallel "$(nproc)" --timeout 900
