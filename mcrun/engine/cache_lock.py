"""Numba's on-disk cache saved under a lock shared by processes, so that processes compiling at
once (``mcrun warm-up``'s, Dask workers on a shared cache folder) lose no entry.

Numba keeps one index file per cached function (``<function>.nbi``: signature -> data file
``<function>.N.nbc``) and saves an entry by reading the index, adding the entry and writing it
back (``numba.core.caching.IndexDataCacheFile.save``). Two processes that compile the same
function for different signatures at once (the batch kernel for the plane and for a terrain,
a callee shared by both) may both read the index before either writes it: the last writer
drops the other's entry, and both may pick the same free data file name, so that one
signature's entry names the other's code. ``locked_saves`` holds an exclusive ``flock`` on the
cache folder for the whole of each save (the index and the data file), which makes a save
atomic against every other process that saves under the same lock. Loading needs no lock:
Numba writes each file under a temporary name and renames it into place.
"""

import contextlib
import functools
import os

try:
    import fcntl
except ImportError:  # Windows: no flock
    fcntl = None


def available():
    """Whether saves can be locked here (POSIX ``flock`` and the Numba cache internals this
    relies on); when not, processes must not compile the same functions at once."""
    if fcntl is None:
        return False
    try:
        from numba.core.caching import IndexDataCacheFile
    except ImportError:
        return False
    return callable(getattr(IndexDataCacheFile, "save", None))


@contextlib.contextmanager
def _folder_lock(folder):
    fd = os.open(folder, os.O_RDONLY)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        yield
    finally:
        os.close(fd)  # releases the lock


def _locked(save):
    @functools.wraps(save)
    def locked_save(self, key, data):
        os.makedirs(self._cache_path, exist_ok=True)
        with _folder_lock(self._cache_path):
            return save(self, key, data)

    locked_save.mcrun_locked = True
    return locked_save


@contextlib.contextmanager
def locked_saves():
    """Within this context, every save to Numba's cache in this process holds an exclusive lock
    on its cache folder (a no-op where ``available()`` is False)."""
    if not available():
        yield False
        return
    from numba.core.caching import IndexDataCacheFile

    save = IndexDataCacheFile.save
    if getattr(save, "mcrun_locked", False):  # already locked by an enclosing context
        yield True
        return
    IndexDataCacheFile.save = _locked(save)
    try:
        yield True
    finally:
        IndexDataCacheFile.save = save
