"""The 3-D animation of a run: :meth:`pysolver.Result.animate` returns an :class:`Animation`,
one self-contained HTML page (three.js inlined, nothing fetched when it is viewed) that plays
every body's motion with the deck's graphics, joints, springs and ground
(docs/animation.md)."""
from __future__ import annotations

import html as _html
import os
from collections.abc import Mapping

from ..model import Model
from .page import html
from .scene import MAX_FRAMES, Scene

__all__ = ["Animation", "Scene"]


class Animation:
    """An animation of a run: shows itself in Jupyter, ``save(path)`` writes the page.

    Parameters
    ----------
    result : pysolver.Result
    model : pysolver.Model
        The model that made `result`.
    params : dict, optional
        The run's numbers (``model.run(params=...)``, a sweep's case), when they move markers.
    max_frames : int or None, optional
        Output rows kept at most (every k-th row and the last beyond; None: all), at least 2.

    Raises
    ------
    TypeError
        `model` is not a Model, `params` not a dict, `max_frames` not an int or None.
    ValueError
        `max_frames` is below 2, or the run has no output rows.

    Attributes
    ----------
    scene : Scene
        What is shown: the poses (``scene.poses``), the items drawn, the notes (the rows kept,
        what is not drawn).
    """

    def __init__(self, result, model, params=None, max_frames=MAX_FRAMES):
        if not isinstance(model, Model):
            raise TypeError(f"animate() takes the Model that made the run, not {model!r}" +
                            (": write the page with res.animate().save(path)"
                             if isinstance(model, (str, os.PathLike)) else
                             f" ({type(model).__name__})"))
        if params is not None and not isinstance(params, Mapping):
            raise TypeError(f"params must be a dict {{path: number}} or None, got {params!r} "
                            f"({type(params).__name__})")
        self.scene = Scene(result, model, params=params, max_frames=max_frames)
        self._html = None

    @property
    def notes(self):
        """The page's note list: which output rows are shown when not all are (first), then
        the elements not drawn, and why."""
        return list(self.scene.notes)

    def html(self) -> str:
        """The page as text."""
        if self._html is None:
            self._html = html(self.scene.data())
        return self._html

    def save(self, path: str | os.PathLike) -> str:
        """Write the page (one HTML file that works offline); return the path written."""
        path = os.fspath(path)
        with open(path, "w", encoding="utf-8") as fh:
            fh.write(self.html())
        return path

    def _repr_html_(self):
        """Jupyter: the page in an iframe of its own (srcdoc: no server, no file)."""
        return (f'<iframe srcdoc="{_html.escape(self.html(), quote=True)}" '
                f'style="width: 100%; height: 520px; border: 1px solid #cfd6dd; '
                f'box-sizing: border-box;" '
                f'title="{_html.escape(self.scene.title)}: animation"></iframe>')

    def __repr__(self):
        p = self.scene.poses
        return (f"<pysolver.Animation of {self.scene.title}: {len(p.t)} frames, "
                f"{len(p.pos)} bodies, {len(self.scene.items)} items>")
