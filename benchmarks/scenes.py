"""The scenes the benchmarks share with the tests, which keep them (tests/scenes.py): this module
loads that file and re-exports its names, so a benchmark script run from this folder imports
``scenes`` as the tests do (under pytest, tests/ comes first on the path and this file is not
used)."""
import importlib.util
import pathlib

_PATH = pathlib.Path(__file__).resolve().parents[1] / "tests" / "scenes.py"
_SPEC = importlib.util.spec_from_file_location("_pysolver_test_scenes", _PATH)
_MODULE = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(_MODULE)
globals().update({k: v for k, v in vars(_MODULE).items() if not k.startswith("__")})
