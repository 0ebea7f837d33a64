"""Batch studies: many cases of one model, compiled once (:func:`pysolver.sweep`)."""
from .design import grid, sample
from .runner import StorageError, Sweep, sweep
from .table import Table

__all__ = ["StorageError", "Sweep", "Table", "grid", "sample", "sweep"]
