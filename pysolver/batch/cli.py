"""``pysolver sweep``: the command-line face of :func:`pysolver.sweep`.

Mistakes raise :class:`pysolver.errors.UsageError` (one line ``pysolver: error: ...``, exit 2).
"""
import argparse
import csv
import math
import os
import re
import sys

from ..errors import DeckError, UsageError
from .design import grid, sample
from .runner import STATUSES, StorageError, sweep

#: Seconds to wait for a Dask scheduler (dask's own default is 30 s and more).
SCHEDULER_TIMEOUT = 5

#: A column as the old spelling gave it: ``--output NAME=SPEC`` (now ``--column``).
_COLUMN = re.compile(r"^[A-Za-z_]\w*=\S+$")


def add_parser(sub, number):
    """The ``sweep`` sub-command of the ``pysolver`` parser; `number(kind, low, words)` is
    the command's argparse type of numbers (:func:`pysolver.cli.number`)."""
    p = sub.add_parser("sweep", help="run a parameter study of a deck (grid, sample or cases)",
                       description="Run a deck once per case (a grid over --set values, a "
                                   "--sample within --set ranges, or --cases from a CSV) and "
                                   "write the table of cases into a folder.")
    p.add_argument("deck", help="deck file (.xml, .py, .adm or .acf)")
    p.add_argument("--set", action="append", default=[], metavar="PATH=V1,V2,...",
                   help="values of a path (a grid over every --set); with --sample: PATH=LO,HI")
    p.add_argument("--cases", metavar="CSV", help="cases as a CSV file, one column per path")
    p.add_argument("--sample", metavar="METHOD:N",
                   help="N cases by sobol or lhs within the --set ranges (seed: --seed)")
    p.add_argument("--seed", type=number(int), default=None)
    p.add_argument("--column", action="append", default=[], metavar="NAME=SPEC",
                   help="a column of the table, a scalar per case, e.g. "
                        "x_end=final:request/1/1 (final, max, min, mean of request/ID/K or a "
                        "state; first_event; steps)")
    p.add_argument("-j", "--processes", type=number(int, -1, "an integer >= 0"), default=None,
                   help="worker processes (default: one per core; 0: in this process)")
    p.add_argument("--timeout", type=number(float, 0.0, "a finite number > 0"), default=None,
                   help="seconds per case")
    p.add_argument("--startup-timeout", type=number(float, 0.0, "a finite number > 0"),
                   default=None, metavar="S",
                   help="seconds a worker may take to load and compile the model (default: "
                        "with --timeout, the larger of it and 300)")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="a Dask scheduler (tcp://...) to run the cases on")
    p.add_argument("-o", "--output", action="append", default=[], metavar="DIR",
                   help="folder: table.csv (and table.parquet with pyarrow), results/, "
                        "cases.jsonl; a second run into it skips the cases already done")
    # the spellings of earlier versions: --out DIR; --output NAME=SPEC for --column
    p.add_argument("--out", action="append", dest="output", help=argparse.SUPPRESS)
    p.add_argument("--keep", default="ok", metavar="STATUS,...",
                   help="statuses of stored cases to reuse (default: ok; the others run "
                        f"again), or all; statuses: {', '.join(STATUSES)}")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=run)


def _folder_and_columns(args):
    """The output folder and the NAME=SPEC columns (--column, and --output NAME=SPEC as
    earlier versions spelled it)."""
    folders = [v for v in args.output if not _COLUMN.match(v)]
    columns = args.column + [v for v in args.output if _COLUMN.match(v)]
    if len(folders) != 1:
        raise UsageError("sweep needs an output folder: -o DIR" if not folders else
                     f"one output folder, not {len(folders)}: {', '.join(folders)}")
    outputs = {}
    for item in columns:
        name, sep, spec = item.partition("=")
        if not sep or not name or not spec:
            raise UsageError(f"--column {item!r}: expected NAME=SPEC")
        outputs[name] = spec
    return folders[0], outputs


def _cases(args):
    if args.cases:
        if args.set or args.sample:
            raise UsageError("give --cases or --set, not both")
        return _read_cases(args.cases)
    if not args.set:
        raise UsageError("no cases: give --set PATH=V1,V2,... (a grid), --sample with --set "
                     "ranges, or --cases CSV")
    values, given = {}, {}
    for item in args.set:
        path, sep, rest = item.partition("=")
        if not sep or not rest:
            raise UsageError(f"--set {item!r}: expected PATH=V1,V2,...")
        if path.lower() in given:
            raise UsageError(f"--set: one path given twice, {given[path.lower()]!r} and "
                             f"{item!r} (paths are case-insensitive); give its values once, "
                             "--set PATH=V1,V2,...")
        given[path.lower()] = item
        try:
            values[path] = [_finite(v) for v in rest.split(",")]
        except ValueError:
            raise UsageError(f"--set {item!r}: values must be numbers") from None
    if args.sample:
        method, _, n = args.sample.partition(":")
        if method not in ("sobol", "lhs") or not n.isdigit():
            raise UsageError(f"--sample {args.sample!r}: expected sobol:N or lhs:N")
        if int(n) < 1:
            raise UsageError(f"--sample {args.sample}: N must be at least 1")
        if any(len(v) != 2 for v in values.values()):
            raise UsageError("--sample METHOD:N takes ranges --set PATH=LO,HI")
        return sample({p: tuple(v) for p, v in values.items()}, int(n), method, args.seed)
    return grid(values)


def _finite(text):
    value = float(text)
    if not math.isfinite(value):
        raise ValueError(text)
    return value


def _read_cases(path):
    """The cases of a CSV file (a header of paths, a row per case), every cell a number."""
    with open(path, newline="", encoding="utf-8-sig") as fh:
        reader = csv.reader(fh)
        header = next(reader, None)
        rows = [r for r in reader if any(c.strip() for c in r)]
    if not header or not any(h.strip() for h in header):
        raise UsageError(f"--cases {path}: empty file (expected a header of paths and a row per "
                     "case)")
    if not rows:
        raise UsageError(f"--cases {path}: no cases (a header and no rows)")
    seen = {}
    for k, name in enumerate(header, start=1):
        low = name.strip().lower()
        if low in seen:
            first = seen[low]
            raise UsageError(f"--cases {path}: columns {first} ({header[first - 1].strip()!r}) "
                             f"and {k} ({name.strip()!r}) name one path (paths are "
                             "case-insensitive); give each path one column")
        seen[low] = k
    cases = []
    for line, row in enumerate(rows, start=2):
        if len(row) != len(header):
            raise UsageError(f"--cases {path}: row {line} has {len(row)} cells, the header "
                         f"{len(header)}")
        case = {}
        for name, cell in zip(header, row):
            try:
                case[name.strip()] = _finite(cell)
            except ValueError:
                raise UsageError(f"--cases {path}: row {line}, column {name.strip()!r}: {cell!r} "
                             "is not a number") from None
        cases.append(case)
    return cases


def _client(address):
    """A dask.distributed Client of the scheduler at `address` (SCHEDULER_TIMEOUT s)."""
    try:
        from dask.distributed import Client
    except ImportError:
        raise UsageError("--scheduler needs dask.distributed (pip install \"pysolver[dask]\")") \
            from None
    try:
        return Client(address, timeout=SCHEDULER_TIMEOUT)
    except OSError:                     # refused or silent: dask retries until the timeout
        raise UsageError(f"--scheduler {address}: no Dask scheduler answered within "
                     f"{SCHEDULER_TIMEOUT} s") from None
    except (ValueError, TypeError) as err:
        raise UsageError(f"--scheduler {address}: {err}") from None


def run(args):
    """Run the sweep the arguments describe; exit status 0 when every case ran (ok or
    failed), 1 when some did not."""
    out, outputs = _folder_and_columns(args)
    cases = _cases(args)
    keep = "all" if args.keep == "all" else [s.strip() for s in args.keep.split(",") if s.strip()]
    client = _client(args.scheduler) if args.scheduler else None
    try:
        sw = sweep(args.deck, cases, processes=args.processes, client=client,
                   timeout=args.timeout, outputs=outputs, directory=out,
                   progress=False if args.quiet else None, keep=keep,
                   startup_timeout=args.startup_timeout)
    except StorageError as err:
        raise UsageError(str(err)) from None
    except ValueError as err:
        if isinstance(err, DeckError):
            raise
        # the API's words for the options (outputs=, keep=) as the command line spells them
        msg = str(err)
        for api, flag in (("output ", "--column "), ("keep: ", "--keep: ")):
            if msg.startswith(api):
                msg = flag + msg[len(api):]
        raise UsageError(msg) from None
    except KeyboardInterrupt:
        print(f"pysolver: interrupted; the cases finished so far are in {out} (run the "
              "same command again to resume)", file=sys.stderr)
        return 130
    finally:
        if client is not None:
            client.close()
    written = [_table(sw, out)]
    print(sw)
    print(f"wrote {', '.join(written)} and results/ in {out}")
    # the cases that did not run to an end, and why (the first few; all are in the table)
    stuck = [r for r in sw.rows if r["status"] not in ("ok", "failed")]
    for r in stuck[:3]:
        print(f"pysolver: case {r['case']} {r['status']}: {r['message']}", file=sys.stderr)
    if len(stuck) > 3:
        print(f"pysolver: ... and {len(stuck) - 3} more cases that did not run (see "
              f"{written[0]})", file=sys.stderr)
    return 0 if not stuck else 1


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
