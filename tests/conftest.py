"""Fixtures shared by the test suite (paths and helpers: helpers.py; scenes shared with the
benchmarks: scenes.py)."""
import pytest

from helpers import DECKS


@pytest.fixture
def decks():
    """The folder of the example decks."""
    return DECKS


def pytest_addoption(parser):
    parser.addoption("--fuzz-cases", type=int, default=300,
                     help="cases of the deck fuzzer in test_fuzz.py (default 300; the long "
                          "campaign: 10000)")
