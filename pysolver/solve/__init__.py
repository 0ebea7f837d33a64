"""Solving: the transient driver and its integrators, the static solvers, and the actors that
act at instants (sensors, output printing)."""
from .run import run_model

__all__ = ["run_model"]
