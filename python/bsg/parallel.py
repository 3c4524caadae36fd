"""``bsg.parallel_env``: the multi-agent environments with PettingZoo's Parallel API.

    env = bsg.parallel_env("SafetyBallCircle2-v0")
    observations, infos = env.reset(seed=0)
    actions = {agent: env.action_space(agent).sample() for agent in env.agents}
    observations, rewards, terminations, truncations, infos = env.step(actions)
    cost = infos["agent_0"]["cost"]

Every agent's cost is ``infos[agent]["cost"]``, beside its cost terms
(``cost_outside_bounds``, ``cost_agent_collisions``, ...); ``env.state()`` is the
global state of centralised critics. The team ends together: when the episode
is terminated or truncated every agent is, and ``env.agents`` empties until the
next ``reset``. ``bsg.parallel_env_ids()`` lists the ids (docs/multi_agent.md).
Keyword arguments change the description (``bodies=3``, ``cost="team"``,
``circle_radius=6``), or ask for frames (``render_mode="rgb_array"``,
``width``, ``height``, ``camera``, as ``bsg.make``). PettingZoo itself is not
needed; its ``parallel_api_test`` passes on every id (tests/python/test_parallel_env.py).

Imports only ``spaces``, ``rendering`` and ``_core`` (docs/python.md#the-package).
"""

from . import _core
from . import rendering as _rendering
from .spaces import box


def parallel_env_ids():
    """Every multi-agent environment id, sorted."""
    return _core.multi_agent_env_ids()


def describe_parallel_env(env_id, **parameters):
    """The resolved multi-agent description of ``env_id`` with ``parameters`` applied, key to text."""
    return dict(_core.describe_multi_agent(env_id, parameters))


class ParallelEnv:
    """One multi-agent environment, PettingZoo's Parallel API (see the module)."""

    def __init__(self, env_id, *, render_mode=None, width=480, height=360, camera="default",
                 **parameters):
        if not isinstance(env_id, str):
            raise TypeError(f"env_id must be a str, got {type(env_id).__name__}")
        self._renderer = _rendering.make_renderer(render_mode, width, height, camera)
        self._env = _core.MultiAgentEnv(env_id, parameters)
        self.render_mode = render_mode
        spec = self._env.spec
        self.bsg_spec = spec
        self.metadata = {**_rendering.METADATA, "name": spec.id, "is_parallelizable": True}
        self.possible_agents = list(spec.agent_names)
        self.agents = []
        self.observation_spaces = {
            agent: box(-spec.observation_bound, spec.observation_bound, (dim,))
            for agent, dim in zip(self.possible_agents, spec.observation_dims)}
        self.action_spaces = {
            agent: box(spec.action_low, spec.action_high, (dim,))
            for agent, dim in zip(self.possible_agents, spec.action_dims)}
        self.state_space = box(-spec.observation_bound, spec.observation_bound, (spec.state_dim,))

    @property
    def unwrapped(self):
        return self

    @property
    def num_agents(self):
        return len(self.agents)

    @property
    def max_num_agents(self):
        return len(self.possible_agents)

    def observation_space(self, agent):
        """The agent's observation space (the same object at every call)."""
        return self.observation_spaces[self._known(agent)]

    def action_space(self, agent):
        """The agent's action space (the same object at every call)."""
        return self.action_spaces[self._known(agent)]

    def reset(self, seed=None, options=None):
        """(observations, infos), one entry per agent. ``seed`` as ``bsg.Env.reset``: the same
        seed plays the same episode; None continues the random stream. ``options`` is accepted
        for PettingZoo's signature and changes nothing (the description is fixed at construction)."""
        if options is not None and not isinstance(options, dict):
            raise TypeError(f"options must be a dict or None, got {type(options).__name__}")
        observations = self._env.reset(seed)
        self.agents = list(self.possible_agents)
        return (dict(zip(self.possible_agents, observations)),
                {agent: {} for agent in self.possible_agents})

    def step(self, actions):
        """(observations, rewards, terminations, truncations, infos), dicts keyed by agent;
        ``infos[agent]["cost"]`` is the agent's cost. ``actions`` maps every live agent to its action."""
        if not self.agents:
            raise RuntimeError(f"{self.bsg_spec.id}: step() after the episode ended (or before "
                               f"reset()); call reset()")
        if not isinstance(actions, dict):
            raise TypeError(f"actions must be a dict from agent to action, got {type(actions).__name__}")
        missing = [agent for agent in self.agents if agent not in actions]
        unknown = [agent for agent in actions if agent not in self.agents]
        if missing or unknown:
            raise ValueError(f"{self.bsg_spec.id}: actions need exactly the agents {self.agents}; "
                             f"missing {missing}, unknown {unknown}")
        observations, rewards, costs, terminated, truncated, terms = self._env.step(
            [actions[agent] for agent in self.possible_agents])
        agents = self.possible_agents
        infos = {agent: {"cost": cost, **term} for agent, cost, term in zip(agents, costs, terms)}
        result = (dict(zip(agents, observations)), dict(zip(agents, rewards)),
                  {agent: terminated for agent in agents}, {agent: truncated for agent in agents},
                  infos)
        if terminated or truncated:
            self.agents = []
        return result

    def state(self):
        """The global state of the last reset or step: every robot's single-agent observation
        (several robots) or the split Ant's whole observation."""
        return self._env.state()

    def render(self):
        """The current frame (render_mode="rgb_array" or "depth_array"), every robot drawn."""
        if self._renderer is None:
            raise RuntimeError(f"{self.bsg_spec.id}: render() needs a render_mode at construction "
                               f"(one of {_rendering.RENDER_MODES})")
        return self._renderer.render_multi_agent(self._env)

    def close(self):
        self._env.close()

    def _known(self, agent):
        if agent not in self.observation_spaces:
            raise KeyError(f"{self.bsg_spec.id}: no agent {agent!r}; agents: {self.possible_agents}")
        return agent

    def __repr__(self):
        return f"<bsg.ParallelEnv {self.bsg_spec.id}>"


def parallel_env(env_id, **options):
    """Makes multi-agent environment ``env_id`` (``parallel_env_ids()``) with PettingZoo's
    Parallel API; ``options`` change its description or ask for frames (see the module)."""
    return ParallelEnv(env_id, **options)
