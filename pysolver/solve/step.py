"""What one IDASolve call returns, for either integrator (see :mod:`.integrator`)."""
import dataclasses

import numpy as np

ROOT_RETURN = 2
TOO_MUCH_WORK = -1
ERR_FAIL, CONV_FAIL = -3, -4

_MESSAGES = {0: "Successful function return.", 1: "Reached specified tstop.",
             2: "Found a root.", -1: "Could not reach endpoint after 'max_num_steps'.",
             -2: "The requested accuracy could not be achieved.",
             -3: "Error test failures occurred too many times.",
             -4: "Convergence test failures occurred too many times.",
             -6: "The linear solver's setup function failed.",
             -8: "The residual function failed unrecoverably.",
             -9: "The residual function failed recoverably too many times.",
             -10: "The root function failed.",
             -12: "The residual function failed at the first call.",
             -22: "IDA rejected its input (IDA_ILL_INPUT): a step bound, the time span or "
                  "the state's scale is not usable (an h_max, h_min or h0_max out of "
                  "proportion to the command, or initial rates that overflow)."}


@dataclasses.dataclass
class Step:
    """Where one IDASolve call ended.

    Attributes
    ----------
    t : float
    y, yp : ndarray
        The state there (owned by the record).
    status : int
        IDA's flag: 0 reached tout, 1 reached tstop, 2 found a root, < 0 failed.
    roots : ndarray of int or None
        On a root return, which root functions crossed (nonzero entries).
    """
    t: float
    y: np.ndarray
    yp: np.ndarray
    status: int
    roots: np.ndarray = None

    @property
    def success(self):
        return self.status >= 0

    @property
    def message(self):
        return _MESSAGES.get(self.status, f"IDA flag {self.status}")
