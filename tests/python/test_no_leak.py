"""Resident memory stays flat over 10^5 steps of a single and of a vector
environment, and over many rejected actions. A leak of one observation array
(~100 B) per step would add ~10 MB; the bound is 1.5 MiB after a warm-up."""

import os

import numpy as np
import pytest

import bsg

pytestmark = pytest.mark.skipif(
    bool(os.environ.get("BSG_SANITIZED")),
    reason="AddressSanitizer's quarantine holds freed memory: resident memory is not flat")

PAGE = os.sysconf("SC_PAGE_SIZE")
BOUND = 1.5 * 2**20


def resident_bytes():
    with open("/proc/self/statm") as statm:
        return int(statm.read().split()[1]) * PAGE


def test_single_env_memory_is_flat_over_1e5_steps():
    env = bsg.make("SafetyBallCircle-v0")
    env.reset(seed=0)
    actions = list(np.random.default_rng(0).uniform(-1, 1, (1000, 2)))

    def run(steps):
        for t in range(steps):
            result = env.step(actions[t % 1000])
            if result[3] or result[4]:
                env.reset()

    run(10_000)  # warm-up: allocators reach their working size
    before = resident_bytes()
    run(100_000)
    grown = resident_bytes() - before
    assert grown < BOUND, f"resident memory grew by {grown / 2**20:.2f} MiB over 1e5 steps"


def test_vector_env_memory_is_flat_over_1e5_steps():
    vector = bsg.VectorEnv("SafetyBallCircle-v0", 4, num_threads=2)
    vector.reset()
    actions = np.random.default_rng(0).uniform(-1, 1, (250, 4, 2))
    for t in range(2_500):
        vector.step(actions[t % 250])
    before = resident_bytes()
    for t in range(25_000):  # 4 environments: 1e5 environment steps
        vector.step(actions[t % 250])
    grown = resident_bytes() - before
    assert grown < BOUND, f"resident memory grew by {grown / 2**20:.2f} MiB over 1e5 steps"


def test_rejected_actions_do_not_leak():
    env = bsg.make("SafetyBallCircle-v0")
    env.reset(seed=0)
    bad = [np.zeros(3), np.array([np.nan, 0.0]), ["x", 1]]

    def run(calls):
        for k in range(calls):
            try:
                env.step(bad[k % 3])
            except ValueError:
                pass

    run(5_000)
    before = resident_bytes()
    run(30_000)
    grown = resident_bytes() - before
    assert grown < BOUND, f"resident memory grew by {grown / 2**20:.2f} MiB"
