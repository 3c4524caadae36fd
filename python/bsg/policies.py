"""A trained run's policy and its evaluation: ``bsg.load_policy`` and ``bsg.evaluate``.

    policy = bsg.load_policy("runs/SafetyBallCircle-v0/ppo-lag/seed_00000")
    env = bsg.make(policy.env_id)
    obs, info = env.reset(seed=0)
    action = policy.act(obs)                       # [act_dim]; a batch [N, obs_dim] gives [N, act_dim]
    result = bsg.evaluate(policy.run_dir, episodes=10)   # the numbers `bsg eval --json` prints

Both use the C++ loader and evaluation of ``bsg eval`` (any family: on-policy, off-policy,
offline), so the actions are the C++ side's bit for bit and ``bsg.evaluate`` gives the same
numbers as ``bsg eval``. A directory that holds no readable run raises ``RuntimeError`` naming
the file at fault (docs/python.md#use-a-trained-policy).
"""

import json
import os

from . import _core
from .spaces import box


class Policy:
    """The policy of a run directory's latest checkpoint.

    ``act(observation, deterministic=True)`` acts on the environment's raw observation (the
    policy's observation standardisation is inside): one observation ``[obs_dim]`` gives one
    action ``[act_dim]``, a batch ``[N, obs_dim]`` gives ``[N, act_dim]``, float64.
    ``deterministic=False`` gives the actions the policy explores with (the on-policy Gaussian's
    sample at the checkpoint's sigma, SAC's squashed sample, TD3's and DDPG's noise), drawn from
    the policy's own stream, which starts where ``bsg eval --actions sampled`` starts.
    """

    def __init__(self, run_dir):
        self._policy = _core.Policy(os.fspath(run_dir))
        spec = self._policy.env_spec
        self.observation_space = box(-spec.observation_bound, spec.observation_bound,
                                     (spec.observation_dim,))
        self.action_space = box(spec.action_low, spec.action_high, (spec.action_dim,))

    def act(self, observation, deterministic=True):
        """The action for ``observation`` (or one per row of a batch)."""
        return self._policy.act(observation, bool(deterministic))

    __call__ = act

    @property
    def run_dir(self):
        return self._policy.run_dir

    @property
    def env_id(self):
        """The id of the environment the run trained on (``bsg.make(policy.env_id)``)."""
        return self._policy.env_id

    @property
    def env_spec(self):
        """bsg's ``EnvSpec`` of the run's environment (its ``env:`` block applied)."""
        return self._policy.env_spec

    @property
    def alg(self):
        return self._policy.alg

    @property
    def epoch(self):
        """Epochs the checkpoint covers (``epochs`` when the run finished)."""
        return self._policy.epochs_completed

    @property
    def epochs(self):
        """Epochs of the run's configuration."""
        return self._policy.epochs

    @property
    def observation_normalization(self):
        """How the policy standardises an observation s before its network, or None when it
        sees raw observations: ``{"mean", "std", "std_epsilon", "clip"}`` with
        s_hat = (s - mean) / (std + std_epsilon), clipped to [-clip, clip] unless clip is None."""
        return self._policy.observation_standardization

    @property
    def config(self):
        """The run's resolved configuration, key -> YAML text (as config.yaml holds it)."""
        return self._policy.config

    def __repr__(self):
        return (f"<bsg.Policy {self.alg} on {self.env_id}, epoch {self.epoch}/{self.epochs}, "
                f"from {self.run_dir}>")


def load_policy(run_dir):
    """The ``Policy`` of ``run_dir``'s latest checkpoint (RuntimeError if it holds no run)."""
    return Policy(run_dir)


def evaluate(run_dir, episodes=None, seed=None, render=None, *, actions=None, camera="arena",
             width=480, height=360):
    """``bsg eval``'s evaluation of ``run_dir`` (or of a ``Policy``'s run directory).

    ``episodes`` (default: the run's ``eval_episodes``), ``seed`` (default: the run's seed, as
    ``bsg eval``; another gives other episodes of the same policy), ``actions`` ("mean" or
    "sampled"; default: the run's ``sampled_evaluation``), ``render``: a path to write the
    episodes to as an MP4 video (as ``bsg eval --video``, with ``camera``, ``width`` and
    ``height``). Returns the dict ``bsg eval --json`` prints (``mean_return`` J, ``mean_cost`` H,
    ``episodes``, ``mean_length``, ``returns``, ``costs``, ``lengths``, ``action_std`` when the
    actions were sampled) with ``epoch`` and ``epochs`` of the checkpoint and, with ``render``,
    ``video`` (its path) and ``video_frames``.
    """
    if isinstance(run_dir, Policy):
        run_dir = run_dir.run_dir
    if render is not None and not isinstance(render, (str, os.PathLike)):
        raise TypeError(f"render must be a path for the MP4 video (or None), got {render!r}")
    for name, value in (("episodes", episodes), ("seed", seed)):
        if value is not None and (isinstance(value, bool) or not isinstance(value, int)):
            raise TypeError(f"{name} must be an int or None, got {value!r}")
    video = os.fspath(render) if render is not None else None
    text, epoch, epochs, frames = _core.evaluate(os.fspath(run_dir), episodes, seed, actions, video,
                                                 camera, width, height)
    result = json.loads(text)
    result["epoch"] = epoch
    result["epochs"] = epochs
    if video is not None:
        result["video"] = video
        result["video_frames"] = frames
    return result
