"""The pysolver command: run a deck, check a deck, or sweep its parameters (pysolver run, check,
sweep; pysolver COMMAND --help for each)."""
import argparse
import csv
import dataclasses
import json
import os
import sys

from .deck.loader import load
from .errors import DeckError


def _command_line_simulate(args, parser):
    """--end, --steps, --dtout: the attributes of one transient command from 0 that replaces
    the deck's commands (None without them)."""
    if args.end is None and args.steps is None and args.dtout is None:
        return None
    if args.end is None:
        parser.error("--steps and --dtout need --end")
    if args.steps is not None and args.dtout is not None:
        parser.error("give --steps or --dtout, not both")
    if not args.end > 0:
        parser.error(f"--end must be > 0, got {args.end:g}")
    sim = {"analysis_type": "TRANSIENT", "end_time": args.end}
    if args.dtout is not None:
        sim["print_interval"] = args.dtout
    else:
        sim["num_step"] = args.steps if args.steps is not None else 100
    return sim


def _run(args):
    model = load(args.deck, user_code=not args.no_user_code,
                 simulate=_command_line_simulate(args, args.parser))
    out = args.output or os.path.splitext(os.path.basename(args.deck))[0] + "_out"
    os.makedirs(out, exist_ok=True)
    # the rows go to the CSV as they are made (a crashing C subroutine loses none of them); it
    # is written again only when a channel with an expression had no value at all (dropped)
    csv_path = os.path.join(out, "requests.csv")
    res = model.run(progress=None if not args.quiet else False, stream=csv_path)
    with open(csv_path, newline="") as fh:
        streamed = next(csv.reader(fh), None)
    if streamed != res.columns()[0] or res.controller_ids:
        res.save(csv_path)
    written = [csv_path] + [os.path.join(out, f"requests_controller{lid}.csv")
                            for lid in res.controller_ids]
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
        json.dump({"success": res.success, "status": res.status, "message": res.message,
                   "stats": res.stats, "timing": res.timing,
                   "meta": {k: v for k, v in res.meta.items() if k != "options"},
                   "options": res.meta["options"],
                   "events": [dataclasses.asdict(e) for e in res.events],
                   "log": res.log}, fh, indent=2)
    for line in res.log:
        print(line)
    print(res.summary())
    written.append(stats_path)
    print(f"wrote {', '.join(written)}")
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


def main(argv=None):
    """Entry point of the ``pysolver`` command; returns the exit status."""
    parser = argparse.ArgumentParser(prog="pysolver", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="run a deck and write requests.csv, requests.png, "
                         "scene.html, stats.json")
    run.add_argument("deck", help="deck file (.xml, .py, .adm or .acf)")
    run.add_argument("-o", "--output", help="output directory (default: DECKNAME_out)")
    run.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    run.add_argument("--no-plot", action="store_true", help="do not write requests.png")
    run.add_argument("--no-animation", action="store_true",
                     help="do not write scene.html (the 3-D animation)")
    run.add_argument("--end", type=float, help="run one transient command to this time "
                     "instead of the deck's commands (with --steps or --dtout)")
    run.add_argument("--steps", type=int, help="output steps of that command (default 100)")
    run.add_argument("--dtout", type=float, help="output interval of that command")
    convert = sub.add_parser("convert", help="write a deck (.xml, .py, .adm or .acf) as "
                             "MotionSolve XML (-o x.xml), an Adams dataset and its command "
                             "file (-o x.adm) or a script of msolve classes (-o x.py)")
    convert.add_argument("deck")
    convert.add_argument("-o", "--output", required=True, help="the file to write; its "
                         "extension (.xml, .adm, .py) chooses the format")
    check = sub.add_parser("check", help="validate a deck and list what it contains (compiles "
                           "it: runs its user subroutine scripts and loads its C libraries)")
    check.add_argument("deck")
    for cmd in (run, check, convert):
        cmd.add_argument("--no-user-code", action="store_true",
                         help="refuse a deck that runs code of its own (a .py deck, a user "
                              "subroutine's script or C library)")
    run.set_defaults(func=_run)
    check.set_defaults(func=_check)
    convert.set_defaults(func=_convert)
    from .batch.cli import add_parser
    add_parser(sub)
    args = parser.parse_args(argv)
    args.parser = parser
    try:
        return args.func(args)
    except DeckError as err:
        print(f"pysolver: error: {err}", file=sys.stderr)
        return 2
    except FileNotFoundError as err:
        print(f"pysolver: error: {err}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
