"""Shared fixtures of the Python tests (run by scripts/test.sh with the wheel installed in .venv)."""

import os
import sys

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXAMPLES = os.path.join(ROOT, "scenes", "examples")
sys.path.insert(0, os.path.join(ROOT, "examples"))


@pytest.fixture(scope="session")
def root():
    return ROOT


@pytest.fixture(scope="session")
def example():
    """The path of an example input: example("living_rect")."""
    return lambda name: os.path.join(EXAMPLES, f"{name}.json")


@pytest.fixture(scope="session")
def cli():
    """The shade-sim binary the Rust tests built (target/debug), for comparing messages."""
    path = os.path.join(ROOT, "target", "debug", "shade-sim")
    assert os.path.exists(path), f"{path}: build it first (cargo build)"
    return path
