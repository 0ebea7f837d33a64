"""``pysolver sweep``: the command-line face of :func:`pysolver.sweep`."""
import csv
import os
import sys

from ..errors import DeckError
from .design import grid, sample
from .runner import STATUSES, StorageError, sweep


def add_parser(sub):
    """The ``sweep`` sub-command of the ``pysolver`` parser."""
    p = sub.add_parser("sweep", help="run a parameter study of a deck (grid, sample or cases)")
    p.add_argument("deck", help="deck file (.xml or .py)")
    p.add_argument("--set", action="append", default=[], metavar="PATH=V1,V2,...",
                   help="values of a path (a grid over every --set); with --sample: PATH=LO,HI")
    p.add_argument("--cases", metavar="CSV", help="cases as a CSV file, one column per path")
    p.add_argument("--sample", metavar="METHOD:N",
                   help="N cases by sobol or lhs within the --set ranges (seed: --seed)")
    p.add_argument("--seed", type=int, default=None)
    p.add_argument("--output", action="append", default=[], metavar="NAME=SPEC",
                   help="a scalar per case, e.g. x_end=final:request/1/1 (final, max, min, "
                        "mean of request/ID/K or a state; first_event; steps)")
    p.add_argument("-j", "--processes", type=int, default=None,
                   help="worker processes (default: one per core; 0: in this process)")
    p.add_argument("--timeout", type=float, default=None, help="seconds per case")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="a Dask scheduler (tcp://...) to run the cases on")
    p.add_argument("-o", "--out", required=True, metavar="DIR",
                   help="directory: table.csv (and table.parquet with pyarrow), results/, "
                        "cases.jsonl; a second run into it skips the cases already done")
    p.add_argument("--keep", default="ok", metavar="STATUS,...",
                   help="statuses of stored cases to reuse (default: ok; the others run "
                        f"again), or all; statuses: {', '.join(STATUSES)}")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=run)


def _cases(args):
    if args.cases:
        if args.set or args.sample:
            raise SystemExit("pysolver: error: give --cases or --set, not both")
        with open(args.cases, newline="") as fh:
            return [{k: _number(v) for k, v in row.items()} for row in csv.DictReader(fh)]
    values = {}
    for item in args.set:
        path, sep, rest = item.partition("=")
        if not sep or not rest:
            raise SystemExit(f"pysolver: error: --set {item!r}: expected PATH=V1,V2,...")
        try:
            values[path] = [float(v) for v in rest.split(",")]
        except ValueError:
            raise SystemExit(f"pysolver: error: --set {item!r}: values must be numbers") \
                from None
    if args.sample:
        method, _, n = args.sample.partition(":")
        if any(len(v) != 2 for v in values.values()) or not n.isdigit():
            raise SystemExit("pysolver: error: --sample METHOD:N takes ranges --set PATH=LO,HI")
        return sample({p: tuple(v) for p, v in values.items()}, int(n), method, args.seed)
    return grid(values)


def _number(text):
    """A CSV cell as a number, or as given (the case's row then says why it is not one)."""
    try:
        return float(text)
    except (TypeError, ValueError):
        return text


def run(args):
    """Run the sweep the arguments describe; exit status 0 when every case ran (ok or
    failed), 1 when some did not."""
    cases = _cases(args)
    outputs = {}
    for item in args.output:
        name, sep, spec = item.partition("=")
        if not sep:
            raise SystemExit(f"pysolver: error: --output {item!r}: expected NAME=SPEC")
        outputs[name] = spec
    client = None
    if args.scheduler:
        from dask.distributed import Client
        client = Client(args.scheduler)
    keep = "all" if args.keep == "all" else [s.strip() for s in args.keep.split(",") if s.strip()]
    try:
        sw = sweep(args.deck, cases, processes=args.processes, client=client,
                   timeout=args.timeout, outputs=outputs, directory=args.out,
                   progress=False if args.quiet else None, keep=keep)
    except StorageError as err:
        print(f"pysolver: error: {err}", file=sys.stderr)
        return 2
    except ValueError as err:
        if isinstance(err, DeckError):
            raise
        print(f"pysolver: error: {err}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"pysolver: interrupted; the cases finished so far are in {args.out} (run the "
              "same command again to resume)", file=sys.stderr)
        return 130
    finally:
        if client is not None:
            client.close()
    written = [_table(sw, args.out)]
    print(sw)
    print(f"wrote {', '.join(written)} and results/ in {args.out}")
    return 0 if all(r["status"] in ("ok", "failed") for r in sw.rows) else 1


def _table(sw, out):
    path = os.path.join(out, "table.csv")
    sw.table.to_csv(path)
    try:
        sw.to_dataframe().to_parquet(os.path.join(out, "table.parquet"))
        path += ", table.parquet"
    except ImportError:                 # no pandas, or no parquet engine (pyarrow)
        pass
    sys.stdout.flush()
    return path
