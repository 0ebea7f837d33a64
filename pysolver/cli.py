"""The pysolver command: run, check, convert or sweep a deck (pysolver COMMAND --help for each).

Every mistake of the user's (a bad option, a deck error, a file that cannot be read or written)
is one line ``pysolver: error: ...`` on standard error and exit status 2, without a traceback.
"""
import argparse
import csv
import dataclasses
import json
import math
import os
import re
import sys
import warnings

import numpy as np

from ._version import __version__
from .deck.loader import load
from .errors import DeckError, DeckWarning, UsageError


class Parser(argparse.ArgumentParser):
    """argparse with the command's one error convention (no usage block, exit status 2)."""

    def error(self, message):
        raise UsageError(message)


def number(kind, low=None, words=""):
    """An argparse type: a finite `kind` (float or int), above `low` when given."""
    def parse(text):
        try:
            value = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"{text!r} is not {'an integer' if kind is int else 'a number'}") from None
        if not math.isfinite(value) or (low is not None and not value > low):
            raise argparse.ArgumentTypeError(f"must be {words or 'finite'}, got {text}")
        return value
    return parse


def _command_line_simulate(args):
    """--end, --steps, --dtout: the attributes of one transient command from 0 that replaces
    the deck's commands (None without them)."""
    if args.end is None and args.steps is None and args.dtout is None:
        return None
    if args.end is None:
        raise UsageError("--steps and --dtout need --end")
    if args.steps is not None and args.dtout is not None:
        raise UsageError("give --steps or --dtout, not both")
    sim = {"analysis_type": "TRANSIENT", "end_time": args.end}
    if args.dtout is not None:
        sim["print_interval"] = args.dtout
    else:
        sim["num_step"] = args.steps if args.steps is not None else 100
    return sim


def _written_for(folder):
    """The deck (absolute path) whose run `folder`'s stats.json records, or None."""
    try:
        with open(os.path.join(folder, "stats.json")) as fh:
            stats = json.load(fh)
        return stats.get("deck") or os.path.abspath(stats["meta"]["deck"])
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        return None


def default_output(deck):
    """The output folder of ``pysolver run DECK`` without -o: the first of ``<stem>_out``,
    ``<stem>_out-2``, ``<stem>_out-3``, ... (in the current folder) that does not exist, is
    empty, or holds a run of this same deck (its stats.json says so); so a/deck.xml and
    b/deck.xml, or deck.xml and deck.adm, never overwrite each other's results."""
    stem = os.path.splitext(os.path.basename(deck))[0] + "_out"
    mine = os.path.abspath(deck)
    for k in range(1, 10000):
        folder = stem if k == 1 else f"{stem}-{k}"
        if not os.path.isdir(folder) and not os.path.exists(folder):
            return folder
        if os.path.isdir(folder) and (not os.listdir(folder) or _written_for(folder) == mine):
            return folder
    raise UsageError(f"no free output folder {stem}-N; give one with -o")


def _output_folder(args):
    out = args.output or default_output(args.deck)
    if os.path.exists(out) and not os.path.isdir(out):
        raise UsageError(f"-o {out}: exists and is not a folder")
    try:
        os.makedirs(out, exist_ok=True)
    except OSError as err:
        raise UsageError(f"-o {out}: cannot make the output folder ({err.strerror})") from None
    if not os.access(out, os.W_OK | os.X_OK):
        raise UsageError(f"-o {out}: cannot write in this folder")
    return out


#: The files ``pysolver run`` writes into its folder, and a LoadControl task's CSV.
OWNED = ("requests.csv", "states.csv", "reactions.csv", "results.npz", "requests.png",
         "scene.html", "stats.json")
_CONTROLLER_CSV = re.compile(r"requests_controller-?[0-9]+\.csv\Z")


def _clear_earlier_run(out, keep=()):
    """Remove an earlier run's files from `out` when it holds one (its stats.json names a
    deck): the names in :data:`OWNED` and ``requests_controller<ID>.csv`` but `keep`, nothing
    else, so that the folder holds this run alone (a file the new run does not write, a plot
    or a states.csv, would show another run than the CSV beside it). Called once the new run
    has ended, so a run that cannot start leaves the earlier one whole. Returns the paths
    removed."""
    if _written_for(out) is None:
        return []
    removed = []
    for name in sorted(os.listdir(out)):
        path = os.path.join(out, name)
        if (name in OWNED or _CONTROLLER_CSV.match(name)) and name not in keep and \
                os.path.isfile(path):
            os.remove(path)
            removed.append(path)
    return removed


def _stats(args, res):
    """What stats.json holds."""
    return {"deck": os.path.abspath(args.deck), "success": res.success, "status": res.status,
            "message": res.message, "stats": res.stats, "timing": res.timing,
            "meta": {k: v for k, v in res.meta.items() if k != "options"},
            "options": res.meta["options"],
            "statics": [{"time": float(s.time), "method": s.method, "success": bool(s.success),
                         "message": s.message, "iterations": int(s.iterations),
                         "imbalance": float(s.imbalance), "error": float(s.error)}
                        for s in res.statics],
            "units": res.units,
            **({"controller_units": res.controller_units()} if res.controller_ids else {}),
            "events": [dataclasses.asdict(e) for e in res.events],
            "log": res.log}


def _write_states(model, res, out):
    """states.csv (time and every state) and, when the deck has joints or motions,
    reactions.csv (each joint's |F| Fx Fy Fz |T| Tx Ty Tz on I's body, each motion's
    reaction), their headers with units as requests.csv's."""
    # the kernel's CSV writer, as requests.csv's
    from .deck.dimensions import header, state_unit, unit_of
    from .results import _write_csv
    time = header("time", res.units["time"])
    written = [os.path.join(out, "states.csv")]
    _write_csv(written[0], [time] + [header(n, state_unit(model, n)) for n in res.state_names],
               _columns(res.t, res.y))
    names, cols = [time], []
    units = {"F": unit_of(model, "force"), "T": unit_of(model, "torque")}
    for jid in res.joint_ids:
        names += [header(f"joint{jid}.{c}", units[c[0]])
                  for c in ("F", "Fx", "Fy", "Fz", "T", "Tx", "Ty", "Tz")]
        cols.append(res.joint(jid))
    for name in res.state_names:
        if name.startswith("motion") and name.endswith(".reaction"):
            names.append(header(name, state_unit(model, name)))
            cols.append(res.motion(int(name[6:].split(".")[0]))[:, None])
    if cols:
        written.append(os.path.join(out, "reactions.csv"))
        _write_csv(written[-1], names, _columns(res.t, *cols))
    return written


def _columns(t, *blocks):
    """Time and the blocks as one (n, columns) array."""
    return np.column_stack([np.asarray(t, float).reshape(-1, 1)] +
                           [np.asarray(b, float).reshape(len(t), -1) for b in blocks])


def _run(args):
    model = load(args.deck, user_code=not args.no_user_code,
                 simulate=_command_line_simulate(args))
    out = _output_folder(args)
    # the rows go to the CSV as they are made (a crashing C subroutine loses none of them); it
    # is written again only when a channel with an expression had no value at all (dropped)
    csv_path = os.path.join(out, "requests.csv")
    res = model.run(progress=None if not args.quiet else False, stream=csv_path)
    earlier = _clear_earlier_run(out, keep=("requests.csv",))
    with open(csv_path, newline="") as fh:
        streamed = next(csv.reader(fh), None)
    if streamed != res.columns(units=True)[0] or res.controller_ids:
        res.save(csv_path)
    written = [csv_path] + [os.path.join(out, f"requests_controller{lid}.csv")
                            for lid in res.controller_ids]
    if args.states:
        written += _write_states(model, res, out)
    if args.npz:
        written.append(res.save(os.path.join(out, "results.npz")))
    if not args.no_plot:
        png_path = os.path.join(out, "requests.png")
        try:
            res.plot(png_path)
            written.append(png_path)
        except ImportError as err:
            print(f"pysolver: no plot ({err})", file=sys.stderr)
    if not args.no_animation:
        html_path = os.path.join(out, "scene.html")
        try:
            res.animate(model).save(html_path)
            written.append(html_path)
        except ValueError as err:           # no output rows to show
            print(f"pysolver: no animation ({err})", file=sys.stderr)
    stats_path = os.path.join(out, "stats.json")
    with open(stats_path, "w") as fh:
        json.dump(_stats(args, res), fh, indent=2)
    for line in res.log:
        print(line)
    print(res.summary())
    written.append(stats_path)
    gone = [path for path in earlier if path not in written]
    print(f"wrote {', '.join(written)}" +
          (f"; removed {', '.join(gone)} (an earlier run's)" if gone else ""))
    if res.status == -600:
        return 130                  # interrupted: the rows so far were written
    return 0 if res.success else 1


def _check(args):
    model = load(args.deck, user_code=not args.no_user_code)
    model.check()
    print(model.summary())
    print("deck is valid")
    return 0


def _convert(args):
    from .convert import convert
    written = convert(args.deck, args.output, user_code=not args.no_user_code)
    print(f"wrote {', '.join(written)}")
    return 0


def parser():
    """The argument parser of the ``pysolver`` command."""
    top = Parser(prog="pysolver", description=__doc__.split("\n\n")[0],
                 epilog="Exit status: 0 done, 1 a run or case failed, 2 a user error "
                        "(one line 'pysolver: error: ...'), 130 interrupted.")
    top.add_argument("--version", action="version", version=f"pysolver {__version__}")
    sub = top.add_subparsers(dest="command", required=True, metavar="COMMAND")
    run = sub.add_parser("run", help="run a deck: requests.csv, plot, scene.html, stats.json",
                         description="Run a deck's commands (or --end) and write its results "
                                     "into a folder.")
    run.add_argument("deck", help="deck file (.xml, .py, .adm or .acf)")
    run.add_argument("-o", "--output", metavar="DIR",
                     help="output folder (default: DECKNAME_out, or DECKNAME_out-2, -3, ... "
                          "when that one holds another deck's run)")
    run.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    run.add_argument("--no-plot", action="store_true", help="do not write requests.png")
    run.add_argument("--no-animation", action="store_true",
                     help="do not write scene.html (the 3-D animation)")
    run.add_argument("--states", action="store_true",
                     help="also write states.csv (every state) and reactions.csv (joints, "
                          "motions)")
    run.add_argument("--npz", action="store_true",
                     help="also write results.npz (states, requests, joints: Result.save)")
    run.add_argument("--end", type=number(float, 0.0, "a finite number > 0"),
                     help="run one transient command to this time instead of the deck's "
                          "commands (with --steps or --dtout)")
    run.add_argument("--steps", type=number(int, 0, "an integer > 0"),
                     help="output steps of that command (default 100)")
    run.add_argument("--dtout", type=number(float, 0.0, "a finite number > 0"),
                     help="output interval of that command")
    check = sub.add_parser("check", help="validate a deck and list what it contains",
                           description="Validate a deck and list what it contains (compiles "
                                       "it: runs its user subroutine scripts and loads its C "
                                       "libraries).")
    check.add_argument("deck", help="deck file (.xml, .py, .adm or .acf)")
    convert = sub.add_parser("convert", help="write a deck as XML, Adams .adm/.acf or msolve .py",
                             description="Write a deck (.xml, .py, .adm or .acf) as MotionSolve "
                                         "XML (-o x.xml), an Adams dataset and its command file "
                                         "(-o x.adm) or a script of msolve classes (-o x.py).")
    convert.add_argument("deck", help="deck file (.xml, .py, .adm or .acf)")
    convert.add_argument("-o", "--output", required=True, metavar="FILE",
                         help="the file to write; its extension (.xml, .adm, .py) chooses the "
                              "format")
    for cmd in (run, check, convert):
        cmd.add_argument("--no-user-code", action="store_true",
                         help="refuse a deck that runs code of its own (a .py deck, a user "
                              "subroutine's script or C library)")
    run.set_defaults(func=_run)
    check.set_defaults(func=_check)
    convert.set_defaults(func=_convert)
    from .batch.cli import add_parser
    add_parser(sub, number)
    return top


def _one_line(text):
    return " ".join(part.strip() for part in str(text).splitlines() if part.strip())


def _show_warning(message, category, filename, lineno, file=None, line=None):
    """A DeckWarning as one line ``pysolver: warning: ...`` on standard error (the deck's
    file, line and statement are in its text); other warnings as Python shows them."""
    if issubclass(category, DeckWarning):
        print(f"pysolver: warning: {_one_line(message)}", file=sys.stderr)
    else:
        _PYTHON_SHOW(message, category, filename, lineno, file, line)


_PYTHON_SHOW = warnings.showwarning


def main(argv=None):
    """Entry point of the ``pysolver`` command; returns the exit status.

    Parameters
    ----------
    argv : list of str, optional
        The arguments (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        0 done, 1 a run (or a sweep's case) failed, 2 a user error (printed as one line
        ``pysolver: error: ...`` on standard error), 130 interrupted, 141 standard output
        closed early (``| head``). A deck's warnings are lines ``pysolver: warning: ...`` on
        standard error.
    """
    with warnings.catch_warnings():
        warnings.showwarning = _show_warning
        return _main(argv)


def _main(argv):
    try:
        args = parser().parse_args(argv)
        status = args.func(args)
        sys.stdout.flush()          # a closed pipe shows here, not at interpreter exit
        return status
    except BrokenPipeError:
        # the reader (head) is gone: nothing more to say, and no message at exit either
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 141
    except (UsageError, DeckError) as err:
        message = _one_line(err)
    except OSError as err:          # a deck or folder that cannot be read or written
        message = _one_line(f"{err.filename}: {err.strerror}" if err.filename and
                            err.strerror else err)
    except KeyboardInterrupt:
        print("pysolver: interrupted", file=sys.stderr)
        return 130
    print(f"pysolver: error: {message}", file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main())
