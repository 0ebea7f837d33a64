"""What the Exudyn work-precision scripts (joints.py, flyball.py) share: the headline match
of each Exudyn point with the fastest pysolver run at equal or smaller error, the words of its
ratio, how a row prints, and what a run records about where it ran."""
import datetime
import importlib.util
import json
import os
import platform
import subprocess
import sys
import time

import numpy as np


def headline(py_rows, ex_rows, **keys):
    """For each successful Exudyn point: the fastest successful pysolver run whose error is at
    most Exudyn's, and Exudyn time / pysolver time (None when no pysolver run is that
    accurate); `keys` names extra fields of the Exudyn row to copy (e.g. exudyn_model="model")."""
    out = []
    for ex in ex_rows:
        if not ex["success"]:
            continue
        ok = [r for r in py_rows if r["success"] and r["max_err_m"] is not None
              and r["max_err_m"] <= ex["max_err_m"]]
        best = min(ok, key=lambda r: r["wall_s"]) if ok else None
        out.append(dict(**{k: ex[v] for k, v in keys.items()}, exudyn_h=ex["h"],
                        exudyn_wall_s=ex["wall_s"], exudyn_max_err_m=ex["max_err_m"],
                        pysolver_integr_tol=best and best["integr_tol"],
                        pysolver_wall_s=best and best["wall_s"],
                        pysolver_max_err_m=best and best["max_err_m"],
                        ratio=best and ex["wall_s"] / best["wall_s"]))
    return out


def fmt_row(r):
    """One result row in words: steps, wall time (or failed), max error, why it stopped."""
    wall = "failed" if r["wall_s"] is None else f"{r['wall_s']:.4g} s"
    err = "-" if r["max_err_m"] is None else f"{r['max_err_m']:.2e} m"
    tail = "" if r["success"] else f"  ({r['message']}, reached t = {r.get('reached_t')})"
    return f"{r['steps']:,} steps, {wall}, max error {err}{tail}"


def plain(d):
    """A dict of numbers as plain floats (for JSON)."""
    return {k: (float(v) if isinstance(v, (int, float, np.floating)) else v)
            for k, v in dict(d or {}).items()}


def speed(ratio):
    """Words for Exudyn time / pysolver time."""
    if ratio >= 1:
        return f"pysolver is {ratio:.1f}x faster at equal or smaller error"
    return f"pysolver is {1 / ratio:.1f}x slower (at equal or smaller error)"


def git(root, *args):
    """git in the checkout at `root` (where pysolver was imported from); None without one."""
    try:
        return subprocess.run(["git", *args], cwd=root, capture_output=True, text=True,
                              check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return None


def machine(pysolver, root):
    """Versions (NumPy, SciPy, Exudyn and its build, pysolver), the commit and the files the
    work tree had modified, the CPU, the load and the date."""
    import exudyn
    import scipy
    cpu = None
    try:
        cpu = next(line.split(":", 1)[1].strip()
                   for line in open("/proc/cpuinfo") if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    dirty = git(root, "status", "--porcelain", "--untracked-files=no")
    return dict(date=datetime.datetime.now().astimezone().isoformat(timespec="seconds"),
                commit=git(root, "rev-parse", "HEAD"),
                work_tree_modified=None if dirty is None else sorted(
                    line.split(maxsplit=1)[1] for line in dirty.splitlines()),
                python=platform.python_version(), numpy=np.__version__,
                scipy=scipy.__version__, exudyn=exudyn.__version__,
                exudyn_build="exudynCPPfast" if "exudyn.exudynCPPfast" in sys.modules
                else "exudynCPP",
                pysolver=getattr(pysolver, "__version__", None), pysolver_path=str(root),
                kernel_module=importlib.util.find_spec("pysolver._kernel").origin,
                platform=platform.platform(), cpu=cpu, cpus=os.cpu_count(),
                load_average_at_start=list(os.getloadavg()))


def save(out, path):
    """Write the report's JSON (its folder made)."""
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, "w") as f:
        json.dump(out, f, indent=1)
        f.write("\n")


def finish(out, path, t_start, root):
    """Stamp the run's length, the load and the commit at its end, save it and say so."""
    out["runtime_s"] = time.perf_counter() - t_start
    out["machine"]["load_average_at_end"] = list(os.getloadavg())
    out["machine"]["commit_at_end"] = git(root, "rev-parse", "HEAD")
    save(out, path)
    print(f"\nwrote {path} in {out['runtime_s']:.0f} s")
