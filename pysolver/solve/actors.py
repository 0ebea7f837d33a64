"""Things that act at instants of a run: the protocol between them and the transient driver.

The driver only integrates, stops at instants and asks the actors. An actor acts

- at **roots** of functions the kernel evaluates in C (sensors: ``nroots > 0``; IDA finds the
  crossings and the driver passes each actor the slice of IDA's root flags that is its own),
- at **times** it names (``next_time``: output printing, and periodic controllers such as
  LoadControl),
- or when an **output row** is written (``on_output``: verbose sensors).

Its actions come back to the driver as a :class:`Flow`: restart IDA, a first step, write a row,
end the command or the run, or go back to the last converged step and approach the instant
again with smaller steps (restore-and-shrink). For that, every actor can ``save`` what an
action may change and ``restore`` it: the driver keeps a snapshot of all actors with each
converged step while a scene needs restore-and-shrink, and nothing otherwise.
"""
import dataclasses
import math


@dataclasses.dataclass
class Flow:
    """What the actions at one instant ask of the driver.

    Attributes
    ----------
    halt : str or None
        The element that ends the run (successfully) here, e.g. ``"Sensor_Event 3"``.
    ret : str or None
        The element that ends the current Simulate command here.
    restart : bool
        Cold-restart IDA at the current state (the equations changed).
    first_step : float or None
        First step after the restart.
    emit : bool
        Write an output row at this instant.
    restored : bool
        The run went back to an earlier converged step (restore-and-shrink).
    """
    halt: int = None
    ret: int = None
    restart: bool = False
    first_step: float = None
    emit: bool = False
    restored: bool = False

    def update(self, other):
        """Combine the requests of a later action at the same instant into this one (a later
        halt or return names its element)."""
        self.halt = other.halt if other.halt is not None else self.halt
        self.ret = other.ret if other.ret is not None else self.ret
        self.restart |= other.restart
        if other.first_step is not None:
            self.first_step = other.first_step if self.first_step is None else \
                min(self.first_step, other.first_step)
        self.emit |= other.emit
        self.restored |= other.restored
        return self


class Actor:
    """Base of the actors: every hook does nothing, so an actor overrides only what it uses.

    Attributes
    ----------
    nroots : int
        Root functions it owns in the kernel's root vector (0 for actors that act at times).
    needs_restore : bool
        The scene needs restore-and-shrink for this actor: the driver then steps one IDA step
        at a time and snapshots every converged step.
    watching : bool
        True while on_output must see every row: the driver then writes rows one at a time.
    """
    nroots = 0
    needs_restore = False
    watching = False

    @property
    def instants(self):
        """Whether the actor acts at instants of its own (roots, times, rows or a restore):
        a run whose actors have none is the batched C path (outputs through print times in
        one call per batch). Actors that act at times override this to say True."""
        return bool(self.nroots) or self.needs_restore or \
            type(self).on_output is not Actor.on_output or \
            type(self).next_time is not Actor.next_time

    def start(self, run):
        """Act at the start of the run (e.g. conditions that already hold); returns a Flow."""
        return Flow()

    def next_time(self, t):
        """The time of the actor's next action, at or after the current time t (math.inf:
        none). The driver makes IDA stop exactly there and calls on_time."""
        return math.inf

    def on_time(self, run):
        """Act at the time next_time named (run.t), moving the schedule on; returns a Flow.
        A change to the state (run.y, run.yp) takes effect with Flow(restart=True)."""
        return Flow()

    def on_roots(self, run, found):
        """Act on IDA's root flags of this actor's functions (nonzero: crossed); returns a Flow."""
        return Flow()

    def on_output(self, t, y, yp):
        """Called after each output row is written (only for actors registered as watchers)."""

    def save(self):
        """What restore-and-shrink must put back: an opaque snapshot."""
        return None

    def restore(self, snapshot, t):
        """Put back a snapshot from save() taken at time t."""
