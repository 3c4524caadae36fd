#!/usr/bin/env bash
# The README's main job: installs what is missing, builds (Release), then
# trains TRPO-L on SafetyBallCircle-v0 for about a minute of one core
# (configs/runs/main_ball_circle_trpo_l.yaml: 150 epochs of 10 000 steps) with
# one progress line per epoch, evaluates the final policy, draws the learning
# curve (scripts/plot_curves.py) and ends with a one-line summary. The run
# directory lands under runs/main/<time>/ with learning_curve.png in it.
# Extra arguments go to `bsg train` (e.g. --set epochs=50, --set seed=3).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install_deps.sh"
BSG_BUILD_TARGET=bsg "$root/scripts/build.sh" release
run_dir="$root/runs/main/$(date +%Y%m%d-%H%M%S)"
"$root/build/release/bsg" train "$root/configs/runs/main_ball_circle_trpo_l.yaml" --out "$run_dir" "$@"
echo "main.sh: run directory $run_dir: $(cd "$run_dir" && echo *)"
/usr/bin/python3 "$root/scripts/plot_curves.py" "$run_dir"
