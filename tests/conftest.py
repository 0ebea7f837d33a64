"""Fixtures shared by the test suite (paths and helpers: helpers.py; scenes shared with the
benchmarks: benchmarks/scenes.py, on the path through pyproject's ``pythonpath``)."""
import pytest

from helpers import DECKS


@pytest.fixture
def decks():
    """The folder of the example decks."""
    return DECKS
