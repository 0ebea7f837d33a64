"""A sweep's directory: a line of ``cases.jsonl`` per finished case and its Result as
``results/<key>.pkl``.

Only this process writes there (workers, local or Dask, send their rows and Results back), and
only finished work: a case's Result is written first (to a temporary name, then renamed), its
line after, with the Result's size and digest. Reading tolerates damage: a line that is not
UTF-8, not JSON or not a row, and a row whose Result is missing or of another size, are cases
not run (they run again). A storage error (a folder that cannot be written, a full disk) stops
the sweep with :class:`StorageError`, naming the file.
"""
import hashlib
import json
import os
import pickle

#: Statuses a row may have.
STATUSES = ("ok", "failed", "error", "crashed", "timeout")
#: Statuses that come with a Result.
WITH_RESULT = ("ok", "failed")


class StorageError(OSError):
    """A sweep's directory cannot be read or written: the sweep stops (the cases stored so
    far are kept; running it again resumes)."""


def _json_default(v):
    item = getattr(v, "item", None)           # NumPy scalars
    return item() if callable(item) else str(v)


class Store:
    """The directory of a sweep (or nothing, when `directory` is None)."""

    def __init__(self, directory):
        self.directory = None if directory is None else os.fspath(directory)
        self.rows = {}                         # key -> stored record (the last line wins)
        self.written = 0
        self._fh = None
        if self.directory is None:
            return
        self.results = os.path.join(self.directory, "results")
        self.file = os.path.join(self.directory, "cases.jsonl")
        for path, what in ((self.directory, "the sweep's directory"),
                           (self.results, "the folder of the Results")):
            if os.path.exists(path) and not os.path.isdir(path):
                raise StorageError(f"{path} is a file, not a folder ({what}); move it away or "
                                   "choose another directory")
        try:
            os.makedirs(self.results, exist_ok=True)
            with open(self.file, "ab+") as fh:
                fh.seek(0)
                raw = fh.read()
                if raw and not raw.endswith(b"\n"):
                    fh.write(b"\n")            # a line cut by a crash: the next starts afresh
        except OSError as err:
            where = self.file if os.path.isdir(self.results) else self.results
            raise _storage_error(f"cannot use {where}: {err.strerror or err}", err) from None
        for line in raw.split(b"\n"):
            rec = _parse(line)
            if rec is not None:
                self.rows[rec.pop("key")] = rec

    def _error(self, path, err):
        return _storage_error(f"cannot write {path}: {err.strerror or err}; the sweep stopped "
                              f"({self.written} cases stored by this run; run it again to "
                              "resume)", err)

    def stored(self, key, keep):
        """The stored row of `key` (status, message, wall, steps, outputs) when its status is
        one of `keep` and its Result (when it has one) is there whole; else None."""
        rec = self.rows.get(key)
        if rec is None or rec["status"] not in keep:
            return None
        if rec["status"] in WITH_RESULT:
            info = rec.get("_result")
            try:
                size = os.stat(self.path(key)).st_size
            except OSError:
                return None
            if not isinstance(info, dict) or info.get("size") != size:
                return None
        return {k: v for k, v in rec.items() if k != "_result"}

    def path(self, key):
        return os.path.join(self.results, f"{key}.pkl")

    def add(self, key, row, blob):
        """Store a finished case: its Result (pickled, when it has one), then its row."""
        if self.directory is None:
            return
        info = None
        if blob is not None:
            path = self.path(key)
            try:
                _write_file(path, blob)
            except OSError as err:
                raise self._error(path, err) from None
            info = {"size": len(blob), "sha256": hashlib.sha256(blob).hexdigest()}
        rec = {k: v for k, v in row.items() if k not in ("case", "resumed")}
        line = json.dumps({"key": key, **rec, "_result": info}, default=_json_default) + "\n"
        try:
            if self._fh is None:
                self._fh = open(self.file, "a", encoding="utf-8")
            self._fh.write(line)
            self._fh.flush()
        except OSError as err:
            raise self._error(self.file, err) from None
        self.rows[key] = {**rec, "_result": info}
        self.written += 1

    def load(self, key):
        """The stored Result of `key`, or None when it is missing or damaged."""
        info = self.rows.get(key, {}).get("_result")
        if not info:
            return None
        try:
            with open(self.path(key), "rb") as fh:
                blob = fh.read()
            if hashlib.sha256(blob).hexdigest() != info.get("sha256"):
                return None
            return pickle.loads(blob)
        except Exception:  # noqa: BLE001 - damaged: the case runs again
            return None

    def close(self):
        if self._fh is not None:
            try:
                self._fh.close()
            except OSError:
                pass
            self._fh = None


def _write_file(path, blob):
    """Write a file whole or not at all (a temporary name, renamed)."""
    tmp = f"{path}.{os.getpid()}.tmp"
    try:
        with open(tmp, "wb") as fh:
            fh.write(blob)
        os.replace(tmp, path)
    except OSError:
        try:
            os.remove(tmp)
        except OSError:
            pass
        raise


def _storage_error(message, err):
    out = StorageError(message)
    out.errno = err.errno
    return out


def _parse(line):
    """A stored record from a line of cases.jsonl, or None when the line is damaged."""
    line = line.strip()
    if not line:
        return None
    try:
        rec = json.loads(line.decode("utf-8"))
    except (UnicodeDecodeError, ValueError):
        return None
    if not isinstance(rec, dict) or not isinstance(rec.get("key"), str) or \
            rec.get("status") not in STATUSES or not isinstance(rec.get("message", ""), str):
        return None
    return rec
