"""Shared fixtures: the programs ctest points at (tests/CMakeLists.txt)."""

import os
import shutil
import sys

import pytest


def _program(variable):
    path = os.environ.get(variable)
    if not path or not shutil.which(path):
        pytest.skip(f"{variable} is not set to a program (run through ctest)")
    return path


@pytest.fixture(scope="session")
def bsg_binary():
    """The `bsg` program of the same build."""
    return _program("BSG_BINARY")


@pytest.fixture(scope="session")
def policy_recorder():
    """tests/python/policy_recorder.cpp: what `bsg eval`'s policy saw and did."""
    return _program("BSG_POLICY_RECORDER")


@pytest.fixture(scope="session")
def trajectory_recorder():
    """tests/python/trajectory_recorder.cpp: C++ rollouts through envs/env.h."""
    return _program("BSG_TRAJECTORY_RECORDER")


def pytest_sessionfinish(session):
    """Exit code 77 (ctest: skipped) when gymnasium or TensorBoard was missing for a test module."""
    for name in ("gymnasium_import", "tensorboard_import"):
        finder = sys.modules.get(name)
        if finder is not None and finder.missing:
            session.exitstatus = finder.SKIP_RETURN_CODE
