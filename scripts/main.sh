#!/usr/bin/env bash
# The README's main job: installs what is missing, builds (Release), then runs a
# small default job and leaves its result in a run directory under runs/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install_deps.sh"
"$root/scripts/build.sh" release
"$root/build/release/bsg" --version
