"""Where a run folder is: a local (or shared, mounted) path, or an fsspec URL (``s3://...``,
``file://...``), and the pyarrow filesystem that reaches it. fsspec is imported only for a URL.
"""

import functools
from pathlib import Path

import pyarrow.fs as pafs


def is_url(folder):
    """Whether ``folder`` is an fsspec URL (``scheme://...``) rather than a path."""
    return isinstance(folder, str) and "://" in folder


@functools.lru_cache(maxsize=8)
def filesystem(url=None):
    """The pyarrow filesystem of a run folder: local for None, else the fsspec one of ``url``."""
    if url is None:
        return pafs.LocalFileSystem()
    import fsspec

    fs, _ = fsspec.core.url_to_fs(url)
    return pafs.PyFileSystem(pafs.FSSpecHandler(fs))


def url_path(url):
    """The path of ``url`` within its filesystem (``s3://bucket/run`` -> ``bucket/run``)."""
    import fsspec

    return fsspec.core.url_to_fs(url)[1].rstrip("/")


def locate(folder):
    """(url or None, filesystem, path in it) of a run folder given as a path or a URL."""
    if is_url(str(folder)):
        url = str(folder).rstrip("/")
        return url, filesystem(url), url_path(url)
    return None, filesystem(None), str(Path(folder).absolute())
