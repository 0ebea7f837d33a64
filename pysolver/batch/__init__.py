"""Batch studies: many cases of one model, compiled once (:func:`pysolver.sweep`)."""
from .design import grid, sample
from .runner import Sweep, sweep

__all__ = ["Sweep", "grid", "sample", "sweep"]
