"""pysolver.settings reads the environment at the time of use, as os.environ.get does (it reads
os.environ's own dict for speed: the values must be the same, set, changed or removed)."""
import pysolver
from pysolver import settings

from helpers import DECKS


def test_settings_follow_the_environment(monkeypatch):
    monkeypatch.delenv("PYSOLVER_BACKEND", raising=False)
    monkeypatch.delenv("PYSOLVER_OUTPUT_BUDGET", raising=False)
    assert settings.backend() is None and settings.output_budget() == settings.OUTPUT_BUDGET
    monkeypatch.setenv("PYSOLVER_BACKEND", "sksundae")
    monkeypatch.setenv("PYSOLVER_OUTPUT_BUDGET", "1e6")
    assert settings.backend() == "sksundae" and settings.output_budget() == 1e6
    monkeypatch.setenv("PYSOLVER_KERNEL", "t\u00e4pes")        # any text reads back as set
    assert settings.kernel() == "t\u00e4pes"
    monkeypatch.delenv("PYSOLVER_BACKEND")
    assert settings.backend() is None


def test_a_changed_kernel_setting_takes_effect_on_the_next_run(monkeypatch):
    monkeypatch.setenv("PYSOLVER_KERNEL", "tapes")
    model = pysolver.load(DECKS / "catenary_bead.xml")
    assert model.run().meta["kernel"] == "tapes"
    monkeypatch.delenv("PYSOLVER_KERNEL")
    assert model.run().meta["kernel"] == "generated"
