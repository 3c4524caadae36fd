"""``bsg.make``: one environment with either API, optionally reset by its next step."""

from .env import Env
from .gymnasium_env import GymnasiumEnv
from .gymnasium_support import IS_1X
from .gymnasium_support import gymnasium as _gymnasium
from .wrappers import NextStepAutoreset


def make(env_id=None, *, api="safety", max_episode_steps=None, autoreset=False,
         disable_env_checker=None, **options):
    """Makes environment ``env_id`` (see ``env_ids()``).

    ``api="safety"`` (default): Safety-Gymnasium's 6-tuple step;
    ``api="gymnasium"``: gymnasium's 5-tuple with the cost in ``info["cost"]``.
    ``max_episode_steps``: truncation length (default: the spec's);
    ``autoreset=True``: an ended episode is reset by the next step
    (``NextStepAutoreset``, or Gymnasium 1.x's ``Autoreset`` for
    ``api="gymnasium"`` when it is importable); ``disable_env_checker`` is
    accepted for gymnasium's and Safety-Gymnasium's callers and changes nothing
    (bsg.make adds no checker). ``render_mode="rgb_array"`` (or
    ``"depth_array"``), ``width=480``, ``height=360``, ``camera="default"`` (or
    ``"arena"``, ``"track"``, ``"top"``) make ``render()`` return frames. Other keyword
    arguments change the description: ``make(id, bombs=12)``,
    ``make(agent="Drone", task="Reach")`` (no id: that agent on that task).
    Unknown ids raise ValueError listing the valid ones.
    """
    if env_id is not None and not isinstance(env_id, str):
        raise TypeError(f"env_id must be a str, got {type(env_id).__name__}")
    if api not in ("safety", "gymnasium"):
        raise ValueError(f"api must be 'safety' or 'gymnasium', got {api!r}")
    if not isinstance(autoreset, bool):
        raise TypeError(f"autoreset must be a bool, got {autoreset!r}")
    if disable_env_checker is not None and not isinstance(disable_env_checker, bool):
        raise TypeError(f"disable_env_checker must be a bool or None, got {disable_env_checker!r}")
    env = Env(env_id, max_episode_steps=max_episode_steps, **options)
    if api == "gymnasium":
        env = GymnasiumEnv(env)
        if autoreset and IS_1X:
            # The same rule, as a gymnasium.Wrapper. Gymnasium 0.x's AutoResetWrapper
            # resets in the same step instead, so there bsg's own wrapper keeps the rule.
            return _gymnasium.wrappers.Autoreset(env)
    return NextStepAutoreset(env) if autoreset else env
