"""What a benchmark run records about where it ran, and the words of its ratios: the one copy
the Exudyn work-precision scripts (joints.py, flyball.py) share."""
import datetime
import importlib.util
import os
import platform
import subprocess
import sys

import numpy as np


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
