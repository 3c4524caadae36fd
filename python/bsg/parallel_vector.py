"""``bsg.parallel_vector_env``: N copies of a multi-agent environment on a C++ thread pool.

    env = bsg.parallel_vector_env("SafetyBallCircle2-v0", num_envs=8)
    observations, infos = env.reset(seed=0)        # observations["agent_0"]: [8, 10]
    actions = {agent: np.zeros((8, 2)) for agent in env.possible_agents}
    observations, rewards, costs, terminations, truncations, infos = env.step(actions)
    state = env.state()                            # [8, 16]

Every value is a dict keyed by agent, as ``bsg.parallel_env``'s, holding one
row per environment: observations ``[num_envs, obs_dim]`` (float64), rewards
and costs ``[num_envs]`` (float64), terminations and truncations
``[num_envs]`` (bool, the team's: the same for every agent). Agents may differ
in observation and action size, so nothing is stacked or padded; when all
sizes are equal, ``stack(observations)`` gives SafePO's
``[num_envs, agents, obs_dim]`` and ``step`` also takes actions stacked so.

An environment whose team episode ended is reset in the same step: its rows
of ``observations`` and ``state()`` are the new episode's, while
``infos[agent]["final_observation"]`` and ``final_state()`` hold what the
step produced (every row; ``infos[agent]["_final_observation"]`` marks the
environments that ended). ``infos[agent]`` also holds every cost term as a
``[num_envs]`` array. ``reset(seed)`` gives environment i the episode of a new
``bsg.parallel_env`` reset with ``seed + i``, whatever was played before;
``reset()`` starts from the constructor's ``seed`` the first time and then
continues each environment's random stream. Results do not depend on
``num_threads`` (0: every hardware thread, at most ``num_envs``).
docs/multi_agent.md#vectorised-multi-agent-environments describes it.

Imports only ``spaces`` and ``_core`` (docs/python.md#the-package).
"""

import numpy as np

from . import _core
from .spaces import box


class ParallelVectorEnv:
    """``num_envs`` copies of a multi-agent environment stepped together (see the module)."""

    def __init__(self, env_id, num_envs, num_threads=0, seed=0, **parameters):
        if not isinstance(env_id, str):
            raise TypeError(f"env_id must be a str, got {type(env_id).__name__}")
        self._env = _core.MultiAgentVectorEnv(env_id, num_envs, num_threads, seed, parameters)
        spec = self._env.spec
        self.bsg_spec = spec
        self.num_envs = self._env.num_envs
        self.num_threads = self._env.num_threads
        self.possible_agents = list(spec.agent_names)
        self.agents = list(self.possible_agents)  # the team never leaves: ended episodes restart
        bound = spec.observation_bound
        self.single_observation_spaces = {
            agent: box(-bound, bound, (dim,)) for agent, dim in zip(self.possible_agents, spec.observation_dims)}
        self.single_action_spaces = {
            agent: box(spec.action_low, spec.action_high, (dim,))
            for agent, dim in zip(self.possible_agents, spec.action_dims)}
        self.observation_spaces = {
            agent: box(-bound, bound, (self.num_envs, dim))
            for agent, dim in zip(self.possible_agents, spec.observation_dims)}
        self.action_spaces = {
            agent: box(spec.action_low, spec.action_high, (self.num_envs, dim))
            for agent, dim in zip(self.possible_agents, spec.action_dims)}
        self.single_state_space = box(-bound, bound, (spec.state_dim,))
        self.state_space = box(-bound, bound, (self.num_envs, spec.state_dim))
        self._term_names = list(spec.cost_term_names)

    def observation_space(self, agent):
        """The agent's batched observation space, ``[num_envs, obs_dim]``."""
        return self.observation_spaces[self._known(agent)]

    def action_space(self, agent):
        """The agent's batched action space, ``[num_envs, act_dim]``."""
        return self.action_spaces[self._known(agent)]

    def reset(self, seed=None, options=None):
        """(observations, infos), dicts keyed by agent. An int ``seed``: environment i is
        reset with ``seed + i`` as a fresh start; None: see the module. ``options`` is
        accepted for PettingZoo's signature and changes nothing."""
        if options is not None and not isinstance(options, dict):
            raise TypeError(f"options must be a dict or None, got {type(options).__name__}")
        observations = self._env.reset(seed)
        return (dict(zip(self.possible_agents, observations)),
                {agent: {} for agent in self.possible_agents})

    def step(self, actions):
        """(observations, rewards, costs, terminations, truncations, infos), dicts keyed by
        agent. ``actions``: a dict from every agent to its ``[num_envs, act_dim]`` array, or,
        when every agent's action size is equal, one ``[num_envs, agents, act_dim]`` array."""
        observations, rewards, costs, terminated, truncated, terms, finals = self._env.step(
            self._per_agent_actions(actions))
        ended = terminated | truncated
        agents = self.possible_agents
        infos = {}
        for k, agent in enumerate(agents):
            info = {name: terms[:, k, j] for j, name in enumerate(self._term_names)}
            info["final_observation"] = finals[k]
            info["_final_observation"] = ended.copy()
            infos[agent] = info
        return (dict(zip(agents, observations)),
                {agent: rewards[:, k] for k, agent in enumerate(agents)},
                {agent: costs[:, k] for k, agent in enumerate(agents)},
                {agent: terminated.copy() for agent in agents},
                {agent: truncated.copy() for agent in agents},
                infos)

    def state(self):
        """The global states of the last reset or step, ``[num_envs, state_dim]``."""
        return self._env.state()

    def final_state(self):
        """The global states the last step produced, before any auto-reset."""
        return self._env.final_state()

    def stack(self, per_agent):
        """SafePO's layout: a dict of ``[num_envs, dim]`` arrays keyed by agent as one
        ``[num_envs, agents, dim]`` array; ValueError if the agents' sizes differ."""
        if not isinstance(per_agent, dict) or set(per_agent) != set(self.possible_agents):
            raise ValueError(f"{self.bsg_spec.id}: stack() needs a dict with exactly the agents "
                             f"{self.possible_agents}")
        arrays = [np.asarray(per_agent[agent]) for agent in self.possible_agents]
        shapes = {array.shape for array in arrays}
        if len(shapes) != 1:
            raise ValueError(f"{self.bsg_spec.id}: the agents' arrays differ in shape "
                             f"({[array.shape for array in arrays]}); keep them per agent")
        return np.stack(arrays, axis=1)

    def close(self):
        self._env.close()

    @property
    def closed(self):
        return self._env.closed

    def _per_agent_actions(self, actions):
        """One action array per agent, agent order, from a dict or a stacked array."""
        if isinstance(actions, dict):
            missing = [agent for agent in self.possible_agents if agent not in actions]
            unknown = [agent for agent in actions if agent not in self.possible_agents]
            if missing or unknown:
                raise ValueError(f"{self.bsg_spec.id}: actions need exactly the agents "
                                 f"{self.possible_agents}; missing {missing}, unknown {unknown}")
            return [actions[agent] for agent in self.possible_agents]
        dims = set(self.bsg_spec.action_dims)
        stacked_shape = (self.num_envs, len(self.possible_agents), next(iter(dims)))
        if len(dims) != 1:
            raise ValueError(f"{self.bsg_spec.id}: the agents' action sizes differ "
                             f"({list(self.bsg_spec.action_dims)}); pass a dict of per-agent arrays")
        array = np.asarray(actions)
        if array.shape != stacked_shape:
            raise ValueError(f"{self.bsg_spec.id}: actions must be a dict from agent to "
                             f"[num_envs, act_dim] arrays or one array of shape {stacked_shape}, "
                             f"got shape {array.shape}")
        return [array[:, k] for k in range(len(self.possible_agents))]

    def _known(self, agent):
        if agent not in self.observation_spaces:
            raise KeyError(f"{self.bsg_spec.id}: no agent {agent!r}; agents: {self.possible_agents}")
        return agent

    def __enter__(self):
        return self

    def __exit__(self, *exc_info):
        self.close()

    def __repr__(self):
        return (f"<bsg.ParallelVectorEnv {self.bsg_spec.id} x{self.num_envs} on "
                f"{self.num_threads} thread(s){' (closed)' if self.closed else ''}>")


def parallel_vector_env(env_id, num_envs, num_threads=0, seed=0, **options):
    """``num_envs`` copies of multi-agent environment ``env_id`` (``bsg.parallel_env_ids()``)
    on a C++ thread pool; ``options`` change its description as for ``bsg.parallel_env``."""
    return ParallelVectorEnv(env_id, num_envs, num_threads, seed, **options)
