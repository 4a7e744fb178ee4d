"""How a command ends when the process is stopped or the system refuses a path.

- SIGTERM (``kill``, ``docker stop``, Slurm at the end of a job's time) and SIGHUP (the
  terminal closed, an ssh connection lost) are turned into ``Terminated``, a
  ``KeyboardInterrupt``, raised in the main thread where Ctrl-C's would be: a run stops the
  same way, removes its temporary files and exits with ``exit_code(signum)``, the shell's code
  for a process ended by that signal (``EXIT_TERMINATED``, 128 + 15, for SIGTERM; 129 for
  SIGHUP) instead of ``EXIT_INTERRUPTED`` (128 + 2, Ctrl-C). SIGKILL cannot be caught: what it
  leaves, a later run removes (``mcrun.results.output.remove_stale``).
- A path with a name longer than the filesystem allows (ENAMETOOLONG, 255 bytes on most) is
  one line naming the path, shortened when it is long itself: ``name_too_long``; a full disk,
  a file-size limit, a folder removed under a run (``SYSTEM_REFUSALS``) one line too:
  ``system_refusal``.
- ``NUMBA_NUM_THREADS`` that Numba cannot start with (0 raised a ValueError at its import) is
  one line too, said before anything imports Numba: ``threads_setting_problem``; so is a
  ``NUMBA_CACHE_DIR`` this process cannot write (``cache_dir_problem``), and a cache that can
  be written nowhere (``is_cache_unwritable``, Numba's RuntimeError as a module of kernels
  imports).

Light on purpose: ``mcrun.cli`` imports it before any command module.
"""

import contextlib
import errno
import os
import signal
import sys
import tempfile
import threading

EXIT_INTERRUPTED = 130
EXIT_TERMINATED = 143
NAME_MAX_BYTES = 255  # most filesystems (ext4, XFS, btrfs, APFS, NTFS in UTF-16 units)
_SHOWN = 100  # characters of a long path shown in a message: the start and the end


# The signals that stop a command as Ctrl-C does (SIGHUP is not on Windows).
STOP_SIGNALS = tuple(
    getattr(signal, name) for name in ("SIGTERM", "SIGHUP") if hasattr(signal, name)
)


class Terminated(KeyboardInterrupt):
    """The process received SIGTERM or SIGHUP (``signum``, SIGTERM if not given); handled
    wherever Ctrl-C's KeyboardInterrupt is."""

    def __init__(self, signum=signal.SIGTERM):
        super().__init__(signum)
        self.signum = signal.Signals(signum)


def exit_code(signum):
    """The shell's exit code for a process ended by ``signum``: 128 + its number."""
    return 128 + int(signum)


# How long after Python drops an interrupt's exception (``sigterm_interrupts``) it comes again.
REDELIVER_S = 0.02


@contextlib.contextmanager
def sigterm_interrupts():
    """Within the block, SIGTERM and SIGHUP (``STOP_SIGNALS``) raise ``Terminated`` in the
    main thread; yields a list that holds each such signal received. Outside the main thread
    they are left as they are, and so is a signal the process was started to ignore (``nohup``
    ignores SIGHUP: the run goes on when the terminal closes; SIGTERM ignored stays so).

    Python runs a signal's handler between two bytecodes of the main thread, whatever it is
    running: within a garbage collector's callback (Dask's client registers one) or a
    ``__del__``, an exception is printed as "Exception ignored" and dropped, and the interrupt
    with it (the command ran on). Within the block such a dropped ``Terminated`` or Ctrl-C's
    ``KeyboardInterrupt`` is delivered again, ``REDELIVER_S`` later, from a thread of its own
    (so that it is not raised within the hook that saw it dropped), and nothing is printed."""
    received = []

    def handler(signum, frame):
        received.append(signum)
        raise Terminated(signum)

    try:
        previous = {
            s: signal.signal(s, handler)
            for s in STOP_SIGNALS
            if signal.getsignal(s) is not signal.SIG_IGN
        }
    except ValueError:  # not the main thread of the main interpreter
        yield received
        return
    previous_hook = sys.unraisablehook

    def unraisable(event):
        dropped = event.exc_value
        if isinstance(dropped, KeyboardInterrupt) and threading.current_thread() is (
            threading.main_thread()
        ):
            signum = dropped.signum if isinstance(dropped, Terminated) else signal.SIGINT
            again = threading.Timer(REDELIVER_S, signal.pthread_kill,
                                    (threading.main_thread().ident, signum))  # fmt: skip
            again.daemon = True
            again.start()
            return
        previous_hook(event)

    sys.unraisablehook = unraisable
    try:
        yield received
    finally:
        sys.unraisablehook = previous_hook
        for signum, was in previous.items():  # (None: a handler set outside Python)
            signal.signal(signum, signal.SIG_DFL if was is None else was)


@contextlib.contextmanager
def interrupts_deferred():
    """Within the block, Ctrl-C, SIGTERM and SIGHUP wait: they take effect as the block ends
    (for a step that cannot be undone once interrupted, as a Dask cluster half started).
    Outside the main thread nothing is deferred."""
    received = []
    signums = (signal.SIGINT, *STOP_SIGNALS)
    try:
        previous = {
            s: signal.signal(s, lambda signum, frame: received.append(signum)) for s in signums
        }
    except ValueError:  # not the main thread of the main interpreter
        yield
        return
    try:
        yield
    finally:
        for signum, handler in previous.items():
            signal.signal(signum, signal.SIG_DFL if handler is None else handler)
        for signum in dict.fromkeys(received):
            signal.raise_signal(signum)  # now handled as it would have been


def interruptible(fn, *args, **kwargs):
    """``fn(*args, **kwargs)`` on a thread of its own, waited for so that Ctrl-C and SIGTERM take
    effect at once: compiled code called from the main thread holds it until it returns, and a
    signal's handler with it (a putt of 100,000 holings-out takes minutes). ``fn`` should
    release the GIL (a ``nogil`` kernel) and leave nothing half written: interrupted, the
    thread is left to finish as the process exits (a daemon, which it does not wait for)."""
    box = {}

    def call():
        try:
            box["result"] = fn(*args, **kwargs)
        except BaseException as err:
            box["error"] = err

    thread = threading.Thread(target=call, name="mcrun-call", daemon=True)
    thread.start()
    thread.join()  # a signal's handler runs here, in the main thread, as it comes
    if "error" in box:
        raise box["error"]
    return box["result"]


def shorten(text, most=_SHOWN):
    """``text`` with its middle replaced by "..." when it has more than ``most`` characters."""
    if len(text) <= most:
        return text
    head = most * 2 // 3
    return f"{text[:head]}...{text[head - most + 3 :]}"


def is_name_too_long(err):
    """Whether an exception is the system's refusal of a name or path that is too long."""
    return isinstance(err, OSError) and err.errno == errno.ENAMETOOLONG


def name_too_long(err):
    """The one-line message of an ENAMETOOLONG OSError: the path (shortened) and its longest
    name, or the length of the whole path when no single name is too long."""
    path = err.filename if err.filename is not None else ""
    path = os.fsdecode(path) if isinstance(path, bytes) else str(path)
    names = [part for part in path.split(os.sep) if part]
    longest = max((len(os.fsencode(part)) for part in names), default=0)
    if longest > NAME_MAX_BYTES:
        reason = (
            f"a name in this path is too long ({longest} bytes; a file or folder name may "
            f"have at most {NAME_MAX_BYTES})"
        )
    else:
        reason = f"the path is too long ({len(os.fsencode(path))} bytes)"
    return f"{shorten(path)}: {reason}"


# What the system refuses a command for where the machine, not mcrun, is at fault: a full disk
# or quota, a file-size limit, a read-only or failing disk, a folder removed or a permission
# taken away while the command ran.
SYSTEM_REFUSALS = frozenset(
    getattr(errno, name)
    for name in "ENOSPC EFBIG EDQUOT EROFS EIO ENOENT EACCES EPERM ENOTDIR".split()
    if hasattr(errno, name)
)


def system_refusal(err):
    """The one line of an OSError in ``SYSTEM_REFUSALS`` (pyarrow's say no file: its message
    then), or None for another exception."""
    if not isinstance(err, OSError) or err.errno not in SYSTEM_REFUSALS:
        return None
    reason = " ".join(str(err.strerror or err).split())
    if err.filename is not None:
        return f"{err.filename}: {reason}"
    return f"a file could not be written or read: {reason}"


def environment_problem(environ=None):
    """What is wrong with the environment's settings of Numba, one line (``NUMBA_NUM_THREADS``,
    then ``NUMBA_CACHE_DIR``); None where nothing is."""
    return threads_setting_problem(environ) or cache_dir_problem(environ)


def cache_dir_problem(environ=None):
    """What is wrong with the environment's ``NUMBA_CACHE_DIR`` (where Numba caches the compiled
    kernels), one line; None where it is unset (or empty, which Numba reads as unset) or a
    folder this process can write, made if missing as Numba makes it. Numba passes over a
    folder it cannot write without a word, and caches beside the sources, or nowhere (a
    read-only cache of compiled kernels is not read either)."""
    text = (os.environ if environ is None else environ).get("NUMBA_CACHE_DIR")
    if not text:
        return None
    if text.startswith("~"):  # (quoted in a shell, or set by a program: a folder named "~")
        return (f"NUMBA_CACHE_DIR={text!r}: ~ is not expanded (Numba would make a folder named "
                "~): allowed: the folder's full path, or unset")  # fmt: skip
    try:
        os.makedirs(text, exist_ok=True)
        with tempfile.TemporaryFile(dir=text):
            pass
    except OSError as err:
        return (
            f"NUMBA_CACHE_DIR={text!r}: cannot write there ({err.strerror or err}): allowed: a "
            "folder this user can write (Numba passes over one it cannot), or unset"
        )
    return None


def is_cache_unwritable(err):
    """Whether an exception is Numba's refusal of a cached function (as its module imports)
    where it can write a cache nowhere (mcrun's sources, the user's cache folder and
    ``NUMBA_CACHE_DIR`` all read-only)."""
    return isinstance(err, RuntimeError) and "no locator available" in str(err)


CACHE_UNWRITABLE = (
    "Numba can write its cache of the compiled kernels nowhere (not beside mcrun's sources, "
    "not in the user's cache folder): set NUMBA_CACHE_DIR to a folder this user can write"
)


def threads_setting_problem(environ=None):
    """What is wrong with the environment's ``NUMBA_NUM_THREADS`` (the threads the kernels run
    on), one line; None where it is unset or a whole number 1 or more."""
    text = (os.environ if environ is None else environ).get("NUMBA_NUM_THREADS")
    if text is None or (text.strip().isdigit() and int(text) >= 1):
        return None
    return (
        f"NUMBA_NUM_THREADS={text!r}: allowed: a whole number 1 or more (the threads the "
        "kernels run on; unset, every core)"
    )
