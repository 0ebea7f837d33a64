"""Command line: ``pysolver run DECK [-o DIR]`` and ``pysolver check DECK``."""
import argparse
import dataclasses
import json
import os
import sys

from .deck.loader import load
from .errors import DeckError


def _run(args):
    model = load(args.deck)
    res = model.run(progress=None if not args.quiet else False)
    out = args.output or os.path.splitext(os.path.basename(args.deck))[0] + "_out"
    os.makedirs(out, exist_ok=True)
    csv_path = res.save(os.path.join(out, "requests.csv"))
    written = [csv_path] + [os.path.join(out, f"requests_controller{lid}.csv")
                            for lid in res.controller_ids]
    if not args.no_plot:
        png_path = os.path.join(out, "requests.png")
        try:
            res.plot(png_path)
            written.append(png_path)
        except ImportError as err:
            print(f"pysolver: no plot ({err})", file=sys.stderr)
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
    model = load(args.deck)
    model.check()
    print(model.summary())
    print("deck is valid")
    return 0


def main(argv=None):
    """Entry point of the ``pysolver`` command; returns the exit status."""
    parser = argparse.ArgumentParser(prog="pysolver", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="run a deck and write requests.csv, requests.png, stats.json")
    run.add_argument("deck", help="deck file (.xml or .py)")
    run.add_argument("-o", "--output", help="output directory (default: DECKNAME_out)")
    run.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    run.add_argument("--no-plot", action="store_true", help="do not write requests.png")
    run.set_defaults(func=_run)
    check = sub.add_parser("check", help="validate a deck and list what it contains")
    check.add_argument("deck")
    check.set_defaults(func=_check)
    from .batch.cli import add_parser
    add_parser(sub)
    args = parser.parse_args(argv)
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
