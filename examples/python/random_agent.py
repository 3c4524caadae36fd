#!/usr/bin/python3
"""A random agent on one environment: Safety-Gymnasium's 6-tuple step.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/random_agent.py [ENV_ID]
"""

import sys

import bsg

env_id = sys.argv[1] if len(sys.argv) > 1 else "SafetyBallCircle-v0"
env = bsg.make(env_id)
env.action_space.seed(0)
print(f"{env_id}: observations {env.observation_space.shape}, actions {env.action_space.shape}, "
      f"{env.spec.max_episode_steps} steps per episode, cost limit {env.spec.cost_limit}")
obs, info = env.reset(seed=0)
for episode in range(3):
    episode_return = episode_cost = 0.0
    terminated = truncated = False
    while not (terminated or truncated):
        obs, reward, cost, terminated, truncated, info = env.step(env.action_space.sample())
        episode_return += reward
        episode_cost += cost
    print(f"episode {episode}: return {episode_return:8.3f}, cost {episode_cost:5.0f} "
          f"({'terminated' if terminated else 'truncated'}); last cost terms {info}")
    obs, info = env.reset()
env.close()
