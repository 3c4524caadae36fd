#!/usr/bin/python3
"""Train, load, evaluate and film a policy from Python, in cells as a notebook runs them.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/train_evaluate_film.py \
        [--out runs/notebook_demo] [--epochs 30] [--steps-per-epoch 2000]

Each ``# %%`` line starts a cell (Jupyter through jupytext, VS Code and Spyder read them so);
run the cells one by one in a notebook, or the whole file as a script. It trains PPO-Lagrangian on
SafetyBallCircle-v0 for a few seconds (it does not learn much in so few steps: give it
``--epochs 200`` for that), then loads the policy, acts with it, evaluates it as ``bsg eval``
does and films one episode into an MP4 (headless: EGL, no display needed). Ctrl-C during training
stops the run at the end of its epoch with a checkpoint; running the file again with ``--resume``
continues it.
"""

# %% Settings: a notebook runs this cell as it is (argparse ignores Jupyter's own arguments).
import argparse
import math
import os

import numpy as np

import bsg

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--out", default="runs/notebook_demo", help="the run directory (a new run)")
parser.add_argument("--epochs", type=int, default=30)
parser.add_argument("--steps-per-epoch", type=int, default=2000)
parser.add_argument("--resume", action="store_true", help="continue the run in --out instead of starting one")
parser.add_argument("--film-size", default="480x360", help="WIDTHxHEIGHT of the video")
args, _ = parser.parse_known_args()

# %% Train: bsg train's run in this process. The config is a dict of the keys of
# configs/README.md (a run file's path works too); keywords override keys as --set does.
curve = []  # (epoch, mean episode return, mean episode cost): what a plot would draw


def show_epoch(row):
    """Called after each epoch with its progress.csv row (a dict of floats)."""
    curve.append((int(row["epoch"]), row["episode_return_mean"], row["episode_cost_mean"]))


if args.resume:
    run_dir = bsg.train(resume=args.out, callback=show_epoch)
else:
    config = {
        "env_id": "SafetyBallCircle-v0",
        "alg": "ppo-lag",
        "seed": 0,
        "epochs": args.epochs,
        "steps_per_epoch": args.steps_per_epoch,
        "eval_episodes": 4,
    }
    run_dir = bsg.train(config, out=args.out, callback=show_epoch)
print(f"trained: {run_dir}")
for epoch, episode_return, episode_cost in curve[-3:]:
    print(f"  epoch {epoch}: mean return {episode_return:8.2f}, mean cost {episode_cost:6.2f}")

# %% Load the policy: actions for one observation or a batch, the C++ policy's bit for bit.
policy = bsg.load_policy(run_dir)
print(policy)
env = bsg.make(policy.env_id)
obs, info = env.reset(seed=0)
action = policy.act(obs)                              # [act_dim], the mean action
batch = policy.act(np.stack([obs] * 8))               # [8, act_dim]
assert np.array_equal(batch[0], action)
print(f"action for the first observation: {np.round(action, 3)}")

# %% Roll one episode by hand with the policy (what bsg.evaluate does for you).
episode_return = episode_cost = 0.0
terminated = truncated = False
while not (terminated or truncated):
    # The Gaussian's mean may leave [-1, 1]: the Ball clips it itself (warning once); clip it here.
    action = np.clip(policy.act(obs), env.action_space.low, env.action_space.high)
    obs, reward, cost, terminated, truncated, info = env.step(action)
    episode_return += reward
    episode_cost += cost
env.close()
print(f"one episode by hand: return {episode_return:.2f}, cost {episode_cost:.0f}")

# %% Evaluate as `bsg eval` does: J (mean return) and H (mean cost) over the run's episodes.
result = bsg.evaluate(run_dir, episodes=4)
print(f"evaluation over {result['episodes']} episodes: J {result['mean_return']:.2f}, "
      f"H {result['mean_cost']:.2f} (cost limit {env.spec.cost_limit:g})")
assert math.isfinite(result["mean_return"])

# %% Film one episode (headless, EGL): an MP4 beside the run, the arena camera.
width, height = (int(n) for n in args.film_size.split("x"))
video = os.path.join(run_dir, "episode.mp4")
filmed = bsg.evaluate(run_dir, episodes=1, render=video, camera="arena", width=width, height=height)
print(f"filmed one episode: {filmed['video']} ({filmed['video_frames']} frames, return "
      f"{filmed['mean_return']:.2f}, cost {filmed['mean_cost']:.0f})")
