"""Offline safe-RL datasets in DSRL's HDF5 layout, as ``bsg collect`` writes
them (docs/datasets.md).

    from bsg import datasets
    data = datasets.load("ballcircle.hdf5")   # dict of NumPy arrays, as DSRL's get_dataset()
    info = datasets.attributes("ballcircle.hdf5")
    r, c = datasets.normalized_score(reward, cost, info["cost_limit"],
                                     info["min_episode_reward"], info["max_episode_reward"])

``load`` reads every array of the file and runs the checks DSRL's
``OfflineEnv.get_dataset`` runs (keys present, one row per transition,
``(N, 1)`` vectors flattened, float32 arrays); it raises ValueError with one
line naming the file and the fault, a truncated or corrupted file included
(h5py's own OSError names neither). It needs h5py (Debian's python3-h5py),
imported only when a file is read, so that ``import bsg`` works without it.

This file imports nothing else of the package (docs/python.md#the-package).
"""

import os

import numpy as np

REQUIRED_KEYS = ("observations", "next_observations", "actions", "rewards", "costs", "terminals", "timeouts")
_FLOAT_KEYS = ("observations", "next_observations", "actions", "rewards", "costs")


def _h5py():
    try:
        import h5py
    except ImportError as error:  # pragma: no cover - depends on the machine
        raise ImportError("bsg.datasets needs h5py (Debian: python3-h5py)") from error
    return h5py


def _unreadable(path, error):
    """ValueError naming the file for h5py's error on a damaged one (a truncated copy, flipped bytes)."""
    detail = " ".join(str(error).split())
    return ValueError(f"dataset file {path}: truncated or corrupted ({detail})")


def _open(path):
    h5py = _h5py()
    if not os.path.isfile(path):
        raise ValueError(f"dataset file {path}: no such file")
    if not h5py.is_hdf5(path):
        raise ValueError(f"dataset file {path}: not an HDF5 file")
    try:
        return h5py.File(path, "r")
    except OSError as error:
        raise _unreadable(path, error) from error


def load(path):
    """Every array of the file as a dict of NumPy arrays, checked as DSRL checks them."""
    h5py = _h5py()
    data = {}
    with _open(path) as f:
        def visit(name, item):
            if isinstance(item, h5py.Dataset):
                data[name] = item[()]
        try:
            f.visititems(visit)
        except OSError as error:  # a chunk that does not inflate, an object header cut off
            raise _unreadable(path, error) from error
    for key in REQUIRED_KEYS:
        if key not in data:
            raise ValueError(f"dataset file {path}: missing key '{key}' (a DSRL dataset has "
                             + ", ".join(REQUIRED_KEYS) + ")")
    n = data["observations"].shape[0]
    if data["observations"].ndim != 2 or data["actions"].ndim != 2:
        raise ValueError(f"dataset file {path}: observations and actions must be matrices, got shapes "
                         f"{data['observations'].shape} and {data['actions'].shape}")
    for key in REQUIRED_KEYS[1:]:
        array = data[key]
        if array.ndim == 2 and array.shape[1] == 1 and key not in ("next_observations", "actions"):
            data[key] = array = array[:, 0]
        if array.shape[0] != n:
            raise ValueError(f"dataset file {path}: '{key}' has {array.shape[0]} rows, observations {n}")
        if key not in ("next_observations", "actions") and array.ndim != 1:
            raise ValueError(f"dataset file {path}: '{key}' has shape {array.shape}, expected ({n},)")
    if data["next_observations"].shape != data["observations"].shape:
        raise ValueError(f"dataset file {path}: next_observations has shape {data['next_observations'].shape}, "
                         f"observations {data['observations'].shape}")
    for key in _FLOAT_KEYS:
        data[key] = data[key].astype(np.float32)
    return data


def attributes(path):
    """The file's attributes (how it was made, the normalisation constants) as a dict of str and float."""
    with _open(path) as f:
        out = {}
        try:
            items = list(f.attrs.items())
        except OSError as error:
            raise _unreadable(path, error) from error
        for name, value in items:
            if isinstance(value, bytes):
                value = value.decode("utf-8")
            elif isinstance(value, np.generic):
                value = value.item()
            out[name] = value
    return out


def episode_returns(data):
    """(reward returns, cost returns, lengths) of the complete episodes of ``load``'s dict.

    An episode ends at a row whose terminals or timeouts is 1, as DSRL splits
    them; rows after the last such row are left out."""
    ends = np.flatnonzero((data["terminals"] == 1) | (data["timeouts"] == 1))
    starts = np.concatenate(([0], ends[:-1] + 1)) if ends.size else np.zeros(0, dtype=int)
    rewards = np.asarray(data["rewards"], dtype=np.float64)
    costs = np.asarray(data["costs"], dtype=np.float64)
    reward_returns = np.array([rewards[s:e + 1].sum() for s, e in zip(starts, ends)])
    cost_returns = np.array([costs[s:e + 1].sum() for s, e in zip(starts, ends)])
    return reward_returns, cost_returns, ends - starts + 1


def normalized_score(reward, cost, cost_limit, min_episode_reward, max_episode_reward):
    """DSRL's normalised score of an episode's (or a mean's) reward and cost.

    Reward: (R - R_min) / (R_max - R_min), with the dataset's smallest and
    largest episode reward. Cost: (C + eps) / (kappa + eps), with eps = 1 when
    the cost limit kappa is 0 and eps = 0 otherwise; 1 means "exactly at the
    limit", below 1 is safe."""
    if max_episode_reward == min_episode_reward:
        raise ValueError("normalized_score: the dataset's episode rewards span no range "
                         f"(min = max = {min_episode_reward})")
    if cost_limit < 0:
        raise ValueError(f"normalized_score: the cost limit must be >= 0, got {cost_limit}")
    epsilon = 1.0 if cost_limit == 0 else 0.0
    normalized_reward = (reward - min_episode_reward) / (max_episode_reward - min_episode_reward)
    normalized_cost = (cost + epsilon) / (cost_limit + epsilon)
    return normalized_reward, normalized_cost


def file_normalized_score(path, reward, cost, cost_limit=None):
    """normalized_score with the constants stored in the file (its cost_limit unless one is given)."""
    info = attributes(path)
    for key in ("min_episode_reward", "max_episode_reward", "cost_limit"):
        if key not in info:
            raise ValueError(f"dataset file {path}: no attribute {key} (not written by bsg collect?)")
    limit = info["cost_limit"] if cost_limit is None else cost_limit
    return normalized_score(reward, cost, limit, info["min_episode_reward"], info["max_episode_reward"])
