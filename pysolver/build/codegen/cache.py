"""Compile generated C into a shared library, cached on disk by a hash of what made it.

The key hashes what the source is a function of (the scene's compiled arrays and the generator's
own code, :func:`pysolver.build.codegen.key`), the compiler command and flags, the compiler's
version and the kernel header, so a changed generator, header or compiler never reuses a stale
library, and a warm load neither generates nor compiles.

Longer than 400 lines because it is the one gate between files on disk, a foreign compiler
and ``dlopen``: the checks an entry passes before it is loaded, the compiler run in a process
group of its own under a time limit, and the failure markers, on each of which a fallback
depends.

Each entry is the library ``<key>.so`` and a digest of its bytes, ``<key>.sha256``, written
after a complete build. The generated source ends in a record of the full key
(``ps_gen_scene``, :func:`~.emit.scene_record`), so the library itself says which scene it is.
Before an entry is loaded its file is read without following it into ``dlopen``: it must be a
regular file of sane size whose bytes match the digest, a complete ELF image (on ELF systems)
and hold this key's record; an entry that is not (a crash mid-write, a truncated copy
restamped, another scene's library stamped under this key, a FIFO) is rebuilt, never loaded,
and :func:`build` says why. ``csrc/gen.c`` checks the record again after ``dlopen``. Writes go
through a temporary file and an atomic rename, so concurrent processes building the same deck
are safe.

Every way the cache or the compiler can fail ends in a :class:`Fallback` (the tapes run, with
its message in ``res.log``), never in an exception out of the run: no compiler or one that does
not work (:class:`NoCompiler`), a compile past :data:`TIMEOUT` (:class:`CompileTimeout`: the
compiler's whole process group is killed and its build folder removed), generated C that the
compiler rejects (:class:`CompileError`) and a cache folder that cannot be created or written
(:class:`CacheUnusable`). A compile error or time-out leaves a marker ``<key>.failed`` (and the
rejected source ``<key>.c`` for the user to inspect), so later processes do not compile it
again; delete the marker to retry (a time-out is retried under a longer limit).

Location: ``PYSOLVER_CACHE_DIR`` if set, else the platform's cache directory
(``$XDG_CACHE_HOME`` or ``~/.cache`` on Linux, ``~/Library/Caches`` on macOS,
``%LOCALAPPDATA%`` on Windows) under ``pysolver/kernels``.
"""
import collections
import hashlib
import os
import pathlib
import shlex
import shutil
import signal
import stat
import struct
import subprocess
import tempfile
import time

from ... import settings

#: Flags for the generated code: no fast-math (results must match the tapes to rounding and
#: keep IEEE NaN/inf semantics); -fno-math-errno lets sqrt inline.
FLAGS = ("-O2", "-fno-math-errno", "-fPIC", "-shared")

#: Seconds a compile may run before its process group is killed and the tapes run
#: (``PYSOLVER_COMPILE_TIMEOUT`` overrides, see pysolver.settings). The size cap
#: (``codegen.COMPILE_LIMIT``) keeps the compile of accepted C near half a minute; this is the
#: backstop for a compiler that hangs.
TIMEOUT = settings.COMPILE_TIMEOUT

#: Seconds ``CC --version`` may take (at most :data:`TIMEOUT`).
VERSION_TIMEOUT = 10.0

#: Largest library file the cache reads (bytes).
MAX_LIBRARY = 1 << 30

#: The prefix of a library's scene record (``ps_gen_scene``).
RECORD = "pysolver-scene "

#: A build folder this much older than the longest compile is left over by a killed process.
_STALE = 3600.0

Built = collections.namedtuple("Built", "path seconds record rebuilt")
Built.__doc__ = """A library ready to load: its path, the seconds spent compiling it (0.0 from
the cache), the scene record ``ps_gen_open`` must find in it, and why the cached entry was
rebuilt (None when there was none, or it was used)."""


class Fallback(Exception):
    """The generated kernel cannot be built here: the tapes run (the message says why)."""


class NoCompiler(Fallback):
    """No working C compiler: none on PATH, ``CC`` unparsable, or a compiler that does not run
    or exits 0 without writing the library."""


class CompileError(Fallback):
    """The compiler rejected the generated C (remembered in the cache: not compiled again)."""


class CompileTimeout(Fallback):
    """The compile did not finish within :data:`TIMEOUT` seconds."""


class CacheUnusable(Fallback):
    """The kernel cache folder cannot be created or written."""


def compiler():
    """The C compiler command: ``CC`` if set, else cc, gcc or clang from PATH."""
    env = settings.compiler_command()
    if env:
        try:
            cmd = shlex.split(env)
        except ValueError as exc:
            raise NoCompiler(f"CC={env!r} cannot be parsed as a command: {exc}") from None
        if not cmd:
            raise NoCompiler(f"CC={env!r} names no command")
        return cmd
    for name in ("cc", "gcc", "clang"):
        path = shutil.which(name)
        if path:
            return [path]
    raise NoCompiler("no C compiler on PATH (cc, gcc or clang) and CC is not set")


def _kill_group(proc):
    """Kill `proc` and every process of its group (it leads one: ``start_new_session``)."""
    try:
        if os.name == "posix":
            os.killpg(proc.pid, signal.SIGKILL)
        else:
            proc.kill()
    except OSError:
        pass


def _tail(f, size=4000):
    f.seek(0, os.SEEK_END)
    f.seek(max(0, f.tell() - size))
    return f.read().decode(errors="replace").strip()


def run(argv, seconds, cwd=None):
    """Run argv with no input in a process group of its own; return (exit code, the end of its
    standard output, the end of its standard error). Output goes to files, not pipes, so a
    process left holding them cannot block the caller.

    Raises
    ------
    subprocess.TimeoutExpired
        It ran past `seconds`: the whole group was killed (also on any other exception,
        such as KeyboardInterrupt, while waiting).
    OSError
        It could not be started.
    """
    group = {"start_new_session": True} if os.name == "posix" else \
        {"creationflags": getattr(subprocess, "CREATE_NEW_PROCESS_GROUP", 0)}
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        proc = subprocess.Popen(list(argv), stdin=subprocess.DEVNULL, stdout=out, stderr=err,
                                cwd=cwd, **group)
        try:
            code = proc.wait(seconds)
        except BaseException:
            _kill_group(proc)
            proc.wait()
            raise
        return code, _tail(out), _tail(err)


_versions = {}


def _version(cmd):
    """The compiler's ``--version`` output (remembered for the process, failures too)."""
    got = _versions.get(cmd)
    if got is None:
        name = " ".join(cmd)
        try:
            code, out, err = run(list(cmd) + ["--version"],
                                 min(VERSION_TIMEOUT, settings.compile_timeout()))
        except subprocess.TimeoutExpired as exc:
            got = NoCompiler(f"C compiler {name!r} does not run: '--version' did not answer "
                             f"in {exc.timeout:g} s")
        except OSError as exc:
            got = NoCompiler(f"C compiler {name!r} does not run: {exc}")
        else:
            got = out if code == 0 else NoCompiler(
                f"C compiler {name!r} does not run: '--version' exited {code}: "
                f"{' '.join(err.split())[-300:]}")
        _versions[cmd] = got
    if isinstance(got, Exception):
        raise type(got)(str(got))
    return got


def _is_elf_complete(data):
    """Whether an ELF image holds its header tables, loadable segments and sections (True for
    other formats, which are not checked)."""
    if data[:4] != b"\x7fELF":
        return True
    try:
        wide, e, n = data[4] == 2, "<" if data[5] == 1 else ">", len(data)
        at, word = (32, "Q") if wide else (28, "I")
        phoff, shoff = struct.unpack_from(e + 2 * word, data, at)
        phsize, phnum, shsize, shnum = struct.unpack_from(e + "HHHH", data,
                                                          at + (22 if wide else 14))
        # (table offset, entry size, entries, entry format, its type, offset and size fields)
        tables = ((phoff, phsize, phnum, "II" + 4 * word if wide else "IIIII",
                   (0, 2, 5) if wide else (0, 1, 4)), (shoff, shsize, shnum, "II" + 4 * word,
                                                       (1, 4, 5)))
        for k, (off, size, num, fmt, (t, o, z)) in enumerate(tables):
            if off + num * size > n:
                return False
            for i in range(num):
                f = struct.unpack_from(e + fmt, data, off + i * size)
                # a PT_LOAD segment, or a section other than SHT_NOBITS, past the end
                if (f[t] == 1 if k == 0 else f[t] != 8) and f[o] + f[z] > n:
                    return False
    except (struct.error, IndexError):
        return False
    return True


def _inspect(data, record):
    """Why library bytes `data` may not be loaded as the scene of `record` (None: they may)."""
    if not _is_elf_complete(data):
        return "is truncated (its headers name bytes past its end)"
    mark = RECORD.encode()
    if (record.encode() + b"\0") in data:
        return None
    if mark in data:
        return "was generated for another scene (its scene record differs)"
    return "has no scene record"


def _read_regular(path, most):
    """The bytes of the regular file at path (at most `most`), read without blocking: a FIFO,
    a device or a folder there is refused (ValueError), never opened for reading."""
    st = os.stat(path)
    if not stat.S_ISREG(st.st_mode):
        raise ValueError("is not a regular file")
    if st.st_size > most:
        raise ValueError(f"has an implausible size ({st.st_size} bytes)")
    fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0))
    with os.fdopen(fd, "rb") as f:
        if not stat.S_ISREG(os.fstat(f.fileno()).st_mode):
            raise ValueError("is not a regular file")
        return f.read(most + 1)


def _check_entry(lib, stamp, record):
    """Why the cache entry (lib, stamp) may not be loaded as `record`: None if it may, "" if
    there is none."""
    try:
        text = _read_regular(stamp, 256)
    except FileNotFoundError:
        return ""
    except ValueError as exc:
        return f"its stamp {exc}"
    except OSError as exc:
        return f"its stamp cannot be read ({exc.strerror or exc})"
    try:
        want = text.decode("ascii").strip()
    except UnicodeDecodeError:
        return "its stamp is not a digest (non-ASCII bytes)"
    if len(want) != 64 or any(c not in "0123456789abcdef" for c in want):
        return "its stamp is not a digest"
    try:
        data = _read_regular(lib, MAX_LIBRARY)
        if not data:
            return "its library is empty"
    except FileNotFoundError:
        return "its library is missing"
    except ValueError as exc:
        return f"its library {exc}"
    except OSError as exc:
        return f"its library cannot be read ({exc.strerror or exc})"
    if hashlib.sha256(data).hexdigest() != want:
        return "its library does not match its digest"
    why = _inspect(data, record)
    return None if why is None else f"its library {why}"


def _read_failure(marker):
    """The (kind, seconds, message) of a failure marker, or None when there is none."""
    try:
        text = _read_regular(marker, 8192).decode(errors="replace")
    except (OSError, ValueError):
        return None
    head, _, message = text.partition("\n")
    kind, _, seconds = head.partition(" ")
    try:
        seconds = float(seconds) if seconds else 0.0
    except ValueError:
        seconds = 0.0
    return kind, seconds, message.strip()


def _write_atomic(path, text, tmp):
    """Write text to path through a temporary file in folder tmp and a rename."""
    part = pathlib.Path(tmp) / (path.name + ".part")
    part.write_text(text, encoding="utf-8")
    os.replace(part, path)


def _sweep(folder, limit):
    """Remove build folders a killed process left (older than any compile can run)."""
    try:
        entries = list(os.scandir(folder))
    except OSError:
        return
    now = time.time()
    for entry in entries:
        try:
            if entry.name.startswith(".build-") and entry.is_dir(follow_symlinks=False) and \
                    now - entry.stat(follow_symlinks=False).st_mtime > max(2.0 * limit, _STALE):
                shutil.rmtree(entry.path, ignore_errors=True)
        except OSError:
            pass


def build(scene_key, make_source, include):
    """Return the compiled library of a scene (:class:`Built`), from the cache or compiled.

    Parameters
    ----------
    scene_key : str
        Everything the generated source is a function of (see :func:`pysolver.build.codegen.key`).
    make_source : callable
        ``make_source(record)`` returns the C source, ending in the scene record `record`
        (:func:`~.emit.scene_record`); called only on a cache miss.
    include : str
        The folder of pysolver.h.

    Raises
    ------
    Fallback
        The library cannot be had (the message says why; the tapes run).
    """
    cmd = tuple(compiler())
    name = " ".join(cmd)
    full = hashlib.sha256("\0".join((scene_key, name, " ".join(FLAGS), _version(cmd),
                                     _header(include))).encode()).hexdigest()
    record, key = RECORD + full, full[:32]
    folder = settings.cache_dir()
    lib, stamp = folder / f"{key}.so", folder / f"{key}.sha256"
    marker, kept = folder / f"{key}.failed", folder / f"{key}.c"
    why = _check_entry(lib, stamp, record)
    if why is None:
        return Built(lib, 0.0, record, None)
    limit = settings.compile_timeout()
    failed = _read_failure(marker)
    if failed is not None:
        kind, seconds, message = failed
        if kind == "error":
            raise CompileError(f"the generated C failed to compile with {name!r} in an earlier "
                               f"run (remembered in {marker}: delete it to retry; source in "
                               f"{kept}): {message}")
        if kind == "timeout" and seconds >= limit:
            raise CompileTimeout(f"the generated C did not compile with {name!r} within "
                                 f"{seconds:g} s in an earlier run (remembered in {marker}: "
                                 "delete it or raise PYSOLVER_COMPILE_TIMEOUT to retry)")
    rebuilt = f"the cached library {lib} was rebuilt: {why}" if why else None
    try:
        folder.mkdir(parents=True, exist_ok=True)
        _sweep(folder, limit)
        tmp = tempfile.mkdtemp(dir=folder, prefix=".build-")
    except OSError as exc:
        raise CacheUnusable(f"the kernel cache {folder} is unusable: "
                            f"{exc.strerror or exc}") from None
    try:
        return _compile(cmd, make_source(record), include, limit, pathlib.Path(tmp), folder,
                        key, record, rebuilt)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def _compile(cmd, source, include, limit, tmp, folder, key, record, rebuilt):
    """Compile source in build folder tmp into the cache entry `key` (see :func:`build`)."""
    name = " ".join(cmd)
    lib, stamp = folder / f"{key}.so", folder / f"{key}.sha256"
    marker, kept = folder / f"{key}.failed", folder / f"{key}.c"
    src, out = tmp / "kernel.c", tmp / "kernel.so"
    start = time.perf_counter()
    try:
        src.write_text(source, encoding="utf-8")
    except OSError as exc:
        raise CacheUnusable(f"the kernel cache {folder} is unusable: cannot write the "
                            f"source ({exc.strerror or exc})") from None
    argv = list(cmd) + list(FLAGS) + [f"-I{include}", str(src), "-o", str(out), "-lm"]
    try:
        code, _, err = run(argv, limit, cwd=tmp)
    except subprocess.TimeoutExpired:
        _remember(marker, f"timeout {limit:g}\n", tmp)
        raise CompileTimeout(f"the generated C did not compile with {name!r} within {limit:g} s: "
                             "the compiler was killed (PYSOLVER_COMPILE_TIMEOUT sets the "
                             "limit)") from None
    except OSError as exc:
        raise NoCompiler(f"C compiler {name!r} does not run: {exc}") from None
    if code < 0:
        raise CompileError(f"the C compiler {name!r} was killed by signal {-code} compiling the "
                           "generated C")
    if code != 0:
        # one line, naming the kept source rather than the build folder about to go
        detail = " ".join(err.replace(str(src), str(kept)).split())[-400:] or \
            f"exit status {code}"
        try:
            os.replace(src, kept)
            where = f"source kept in {kept}"
        except OSError:
            where = "the source could not be kept"
        _remember(marker, f"error\n{detail}", tmp)
        raise CompileError(f"the generated C failed to compile with {name!r} ({where}; not "
                           f"compiled again while {marker} exists): {detail}")
    try:
        data = _read_regular(out, MAX_LIBRARY)
    except (OSError, ValueError):
        data = b""
    if not data:
        raise NoCompiler(f"C compiler {name!r} exited 0 but wrote no library")
    why = _inspect(data, record)
    if why is not None:
        raise NoCompiler(f"C compiler {name!r} exited 0 but the library it wrote {why}")
    try:
        os.replace(out, lib)
        _write_atomic(stamp, hashlib.sha256(data).hexdigest(), tmp)
    except OSError as exc:
        raise CacheUnusable(f"the kernel cache {folder} is unusable: cannot store the library "
                            f"({exc.strerror or exc})") from None
    for path in (marker, kept):          # an earlier failure (a time-out, since retried)
        try:
            os.remove(path)
        except OSError:
            pass
    return Built(lib, time.perf_counter() - start, record, rebuilt)


def _remember(marker, text, tmp):
    """Write a failure marker; a cache that cannot take it only loses the memory."""
    try:
        _write_atomic(marker, text, tmp)
    except OSError:
        pass


_headers = {}


def _header(include):
    got = _headers.get(include)
    if got is None:
        got = _headers[include] = (pathlib.Path(include) / "pysolver.h").read_text()
    return got
