#!/usr/bin/env bash
# The README's main job: installs what is missing, builds (Release), then runs a
# small default training job — TRPO-L on SafetyBallCircle-v0 for a few short
# epochs (configs/runs/tiny_ball_circle_trpo_l.yaml) — with one progress line
# per epoch, and leaves a run directory under runs/main/.
# Extra arguments go to `bsg train` (e.g. --set epochs=10).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install_deps.sh"
BSG_BUILD_TARGET=bsg "$root/scripts/build.sh" release
run_dir="$root/runs/main/$(date +%Y%m%d-%H%M%S)"
"$root/build/release/bsg" train "$root/configs/runs/tiny_ball_circle_trpo_l.yaml" --out "$run_dir" "$@"
echo "main.sh: run directory $run_dir"
ls "$run_dir"
