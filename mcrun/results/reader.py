"""Reading a run folder back, whichever executor wrote it.

A finished run folder holds ``summary.parquet`` (one row per point; its metadata holds the run's
provenance) and its shots in one of two layouts:

- ``"file"``: ``shots.parquet`` (the local executor, ``mcrun.run.local``), row groups in point
  and shot order, with min/max statistics of ``point``; ``trajectories.parquet`` likewise.
- ``"dataset"``: ``shots/part-NNNNN.parquet``, or ``shots/group=<name>/part-NNNNN.parquet`` when
  the scenario has groups (the Dask executor, ``mcrun.run.distributed``): one part and one row
  group per chunk, NNNNN the chunk, the chunks numbered point by point, ``ceil(n /
  chunk_size)`` a point; ``trajectories/part-NNNNN.parquet`` likewise (a part per chunk that
  holds a path). Complete only once ``_SUCCESS`` is there.

``open_run`` tells them apart and returns a ``RunFolder``: the summary and the provenance (the
data and its metadata), and the shots and trajectories, either whole (``shots``,
``trajectories``: the DataFrame the local file reads as in pandas, whatever the layout) or one
point at a time (``shot_batches``, ``trajectory_batches``: only the files and row groups that
may hold the point, only the columns asked for, in batches), so that memory does not grow with
the run; and the geometry the run recorded (``geometry``: the frame, tee, pin, aim and
targets, ``hole_map``: the map of its hole, ``mcrun.results.geometry``), None for a run
written before runs recorded it. A folder is a path or an fsspec URL (``location``).
"""

import os
import urllib.parse
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.dataset as ds
import pyarrow.fs as pafs
import pyarrow.parquet as pq

from mcrun.results import geometry, location, output
from mcrun.units import shown

FILE_LAYOUT = "file"
DATASET_LAYOUT = "dataset"


class RunFolderError(output.OutputError):
    """A folder that is not a complete run, or whose files cannot be read; one line."""


def reason_of(err):
    """The one-line reason of an OSError or an Arrow error."""
    if isinstance(err, OSError):
        return err.strerror or str(err)
    return " ".join(str(err).split())


@dataclass
class RunFolder:
    """A finished run folder, opened: where it is (``path``, the Path given or the URL;
    ``url``, the URL or None; its filesystem ``fs`` and the ``root`` path in it), its
    ``layout`` (``"file"`` or ``"dataset"``), its summary and provenance, the columns of its
    shots in the order of the local executor's shots.parquet, and whether it holds
    trajectories."""

    path: Path | str
    url: str | None
    fs: pafs.FileSystem
    root: str
    layout: str
    summary: pd.DataFrame
    provenance: dict
    shot_columns: list
    has_trajectories: bool
    _point_parts: dict = field(default_factory=dict, repr=False)  # ``_parts``, once a folder
    _hole_map: list = field(default_factory=list, repr=False)  # ``hole_map``, once read

    @property
    def geometry(self):
        """The ``geometry.RunGeometry`` the run recorded (its frame, tee, pin, each point's
        aim and target), None for a run that records none."""
        return geometry.read_geometry(self.provenance)

    def hole_map(self):
        """The ``geometry.HoleMap`` of the run's hole as it recorded it, None on a plane or
        for a run that records none (decoded once)."""
        if not self._hole_map:
            self._hole_map.append(geometry.read_hole_map(self.provenance))
        return self._hole_map[0]

    def schema(self, what=output.SHOTS_FILE):
        """The pyarrow schema of the run's shots (``output.SHOTS_FILE``) or trajectories
        (``output.TRAJECTORIES_FILE``): the file's, or a dataset's (its first part's for the
        trajectories)."""
        if self.layout == FILE_LAYOUT:
            with self.fs.open_input_file(f"{self.root}/{what}") as f:
                return pq.read_schema(f)
        if what == output.SHOTS_FILE:
            return _dataset(self.fs, self.root).schema
        for parts in self._parts(output.TRAJECTORIES_DIR).values():
            for name in parts:
                with self.fs.open_input_file(name) as f:
                    return pq.read_schema(f)
        return output.TRAJECTORY_SCHEMA

    def shots(self, columns=None):
        """The shots as one DataFrame, as pandas reads the local executor's shots.parquet: rows
        by point and shot, the same columns in the same order and types (``group`` a
        categorical of the groups in point order). ``columns``: a subset to read."""
        wanted = self._columns(columns)
        try:
            if self.layout == FILE_LAYOUT:
                return pd.read_parquet(_source(self.url, self.root, output.SHOTS_FILE),
                                       columns=columns if columns is None else wanted)  # fmt: skip
            read = list(dict.fromkeys(["point", "shot", *wanted]))
            frame = _dataset(self.fs, self.root).to_table(columns=read).to_pandas()
        except (OSError, pa.ArrowException) as err:
            why = reason_of(err)
            raise RunFolderError(f"cannot read the shots of {self.path}: {why}") from None
        frame = frame.sort_values(["point", "shot"], kind="stable").reset_index(drop=True)
        if "group" in frame:
            categories = list(dict.fromkeys(self.provenance["groups"]))
            frame["group"] = pd.Categorical(frame["group"].astype(str), categories=categories)
        return frame[wanted]

    def _columns(self, columns, known=None, what="shots"):
        """``columns`` (None: all of ``known``, default the shots') as a list, each one of
        ``known``, none twice."""
        known = list(self.shot_columns if known is None else known)
        if columns is None:
            return known
        if isinstance(columns, str) or not isinstance(columns, list | tuple):
            raise RunFolderError(f"columns {shown(columns)}: allowed: a list of the {what}' "
                                 "column names")  # fmt: skip
        unknown = [c for c in columns if c not in known]
        if unknown:
            raise RunFolderError(f"{self.path}: no column {', '.join(map(str, unknown))} in the "
                                 f"{what}")  # fmt: skip
        twice = [c for c in dict.fromkeys(columns) if list(columns).count(c) > 1]
        if twice:  # (two columns of one name in the frame read)
            raise RunFolderError(f"columns: {', '.join(map(str, twice))} given twice")
        return list(columns)

    def _point(self, point):
        """``point``, one of the run's points (an int from 0); RunFolderError otherwise (a
        point beyond them read as none, True as point 1, 0.0 as a KeyError)."""
        count = len(self.summary)
        if isinstance(point, bool) or not isinstance(point, int | np.integer):
            raise RunFolderError(f"point {shown(point)}: allowed: a whole number, 0 to {count - 1}")
        if not 0 <= point < count:
            raise RunFolderError(f"{self.path}: no point {point}: it has {count}, 0 to {count - 1}")
        return int(point)

    def trajectories(self):
        """The trajectories as one DataFrame, rows by point, shot and time (None when the run
        wrote none)."""
        if not self.has_trajectories:
            return None
        try:
            if self.layout == FILE_LAYOUT:
                return pd.read_parquet(_source(self.url, self.root, output.TRAJECTORIES_FILE))
            tables = []
            for parts in self._parts(output.TRAJECTORIES_DIR).values():
                for name in parts:
                    with self.fs.open_input_file(name) as f:
                        tables.append(pq.read_table(f))
        except (OSError, pa.ArrowException) as err:
            raise RunFolderError(f"cannot read the trajectories of {self.path}: "
                                 f"{reason_of(err)}") from None  # fmt: skip
        if not tables:
            return output.TRAJECTORY_SCHEMA.empty_table().to_pandas()
        frame = pa.concat_tables(tables).to_pandas()
        return frame.sort_values(["point", "shot"], kind="stable").reset_index(drop=True)

    def shot_batches(self, point, columns, batch_rows):
        """Batches (dict column -> numpy array) of ``columns`` (None: all) of the shots of
        ``point``, ``batch_rows`` at most, in shot order; text columns as object arrays. One
        row group at a time."""
        return self._batches(output.SHOTS_FILE, output.SHOTS_DIR, self._point(point),
                             self._columns(columns), batch_rows)  # fmt: skip

    def trajectory_batches(self, point, columns, batch_rows):
        """``shot_batches`` of the trajectories: rows of ``point`` by shot and time."""
        columns = self._columns(columns, output.TRAJECTORY_SCHEMA.names, "trajectories")
        return self._batches(output.TRAJECTORIES_FILE, output.TRAJECTORIES_DIR,
                             self._point(point), columns, batch_rows)  # fmt: skip

    def _parts(self, folder):
        """{point: [paths of its parts, in chunk order]} of a dataset folder."""
        if folder in self._point_parts:
            return self._point_parts[folder]
        chunks_per_point = -(-self.provenance["n"] // self.provenance["chunk_size"])
        selector = pafs.FileSelector(f"{self.root}/{folder}", recursive=True)
        parts = {}
        for info in self.fs.get_file_info(selector):
            chunk = output.part_chunk(info.base_name)
            if info.type == pafs.FileType.File and chunk is not None:
                parts.setdefault(chunk // chunks_per_point, []).append((chunk, info.path))
        parts = {p: [path for _, path in sorted(found)] for p, found in sorted(parts.items())}
        self._point_parts[folder] = parts
        return parts

    def _files(self, file, folder, point):
        if self.layout == FILE_LAYOUT:
            return [f"{self.root}/{file}"]
        return self._parts(folder).get(point, [])

    def _batches(self, file, folder, point, columns, batch_rows):
        if isinstance(batch_rows, bool) or not isinstance(batch_rows, int) or batch_rows < 1:
            raise RunFolderError(f"batch_rows {shown(batch_rows)}: allowed: a whole number >= 1")
        for path in self._files(file, folder, point):
            try:
                with self.fs.open_input_file(path) as source, pq.ParquetFile(source) as f:
                    # A dataset's group is in its folders' names (group=NAME), not its files.
                    hive = "group" in columns and "group" not in f.schema_arrow.names
                    constants = {"group": _hive_group(path)} if hive else {}
                    yield from _point_batches(f, point, columns, batch_rows, constants)
            except (OSError, pa.ArrowException) as err:
                raise RunFolderError(f"cannot read {path}: {reason_of(err)}") from None


def _dataset(fs, root):
    """The shots of a dataset run as a pyarrow dataset (the group from the folder names)."""
    return ds.dataset(
        f"{root}/{output.SHOTS_DIR}", filesystem=fs, format="parquet", partitioning="hive"
    )


def _dataset_columns(fs, root):
    """The columns of a dataset run's shots, in the order of the local executor's
    shots.parquet."""
    names = list(_dataset(fs, root).schema.names)
    if names.index("group") != 1:  # hive-partitioned: the group comes last, from the folders
        names.remove("group")
        names.insert(1, "group")
    return names


def _source(url, root, name):
    """A file of a run folder as pandas takes it: a URL, or a path."""
    return f"{url}/{name}" if url else Path(root) / name


def _point_row_groups(parquet_file, point):
    """Row groups of a file by mcrun whose ``point`` statistics may hold ``point``."""
    metadata = parquet_file.metadata
    names = [metadata.schema.column(j).name for j in range(metadata.num_columns)]
    j = names.index("point")
    groups = []
    for i in range(metadata.num_row_groups):
        st = metadata.row_group(i).column(j).statistics
        if st is None or not st.has_min_max or st.min <= point <= st.max:
            groups.append(i)
    return groups


def _hive_group(path):
    """The group of a dataset's part from its folder's name, ``group=NAME`` (percent-encoded)."""
    folder = path.rsplit("/", 2)[-2]
    return (
        urllib.parse.unquote(folder.removeprefix("group=")) if folder.startswith("group=") else ""
    )


def _point_batches(parquet_file, point, columns, batch_rows, constants=None):
    # One row group at a time: given several, iter_batches buffers them all. The point is read
    # to choose the rows, asked for or not; ``constants``: columns of one value, not in the file.
    constants = constants or {}
    read = list(dict.fromkeys([*(c for c in columns if c not in constants), "point"]))
    batches = (
        batch
        for group in _point_row_groups(parquet_file, point)
        for batch in parquet_file.iter_batches(
            batch_size=batch_rows, row_groups=[group], columns=read
        )
    )
    for batch in batches:
        mine = batch.column("point").to_numpy() == point
        if not mine.any():
            continue
        out = {}
        for name in columns:
            if name in constants:
                out[name] = np.full(int(mine.sum()), constants[name], dtype=object)
                continue
            column = batch.column(name)
            if pa.types.is_dictionary(column.type):
                words = np.array(column.dictionary.to_pylist(), dtype=object)
                out[name] = words[column.indices.to_numpy()][mine]
            else:
                out[name] = column.to_numpy(zero_copy_only=False)[mine]
        yield out


# What tells one run from another in its files' provenance.
RUN_KEYS = ("scenario_name", "start_time_utc", "seed", "n")


def _counts(values):
    """Whether a column of the summary holds whole numbers >= 0 (no NaN: summed as 0)."""
    v = pd.to_numeric(values, errors="coerce").to_numpy(dtype=float)
    return bool(np.all(np.isfinite(v) & (v >= 0) & (v == np.round(v))))


def _span(metadata, column):
    """(least, greatest) value of the whole-number ``column`` of a Parquet file by its row
    groups' statistics, or None where they do not say."""
    names = [metadata.schema.column(j).name for j in range(metadata.num_columns)]
    if column not in names or metadata.num_row_groups == 0:
        return None
    j = names.index(column)
    spans = []
    for i in range(metadata.num_row_groups):
        st = metadata.row_group(i).column(j).statistics
        if st is None or not st.has_min_max or not isinstance(st.min, int):
            return None  # (a column of text is refused where it is read)
        spans.append((st.min, st.max))
    return min(a for a, _ in spans), max(b for _, b in spans)


def _check_of_run(folder, name, metadata, provenance, points):
    """RunFolderError unless the file ``name`` of the run folder (its Parquet ``metadata``) is
    of the run whose summary has ``provenance`` and ``points`` rows: the same run in their
    provenance (``RUN_KEYS``), its points among the summary's and its shots among a point's
    (a copy from another run's folder, or its points or shots renumbered, was drawn)."""
    theirs = output.decode_provenance(metadata.metadata)
    for key in RUN_KEYS:
        if key in provenance and key in theirs and provenance[key] != theirs[key]:
            raise RunFolderError(
                f"{folder}: {name} and {output.SUMMARY_FILE} are not of one run "
                f"({key} {theirs[key]!r} against {provenance[key]!r})"
            )
    span = _span(metadata, "point")
    if span is not None and not (0 <= span[0] and span[1] < points):
        raise RunFolderError(
            f"{folder}: {name} holds points {span[0]} to {span[1]} where "
            f"{output.SUMMARY_FILE} has {points}: not one run's files"
        )
    n = provenance.get("n")
    span = _span(metadata, "shot")
    if span is not None and isinstance(n, int) and not (0 <= span[0] and span[1] < n):
        raise RunFolderError(
            f"{folder}: {name} holds shots {span[0]} to {span[1]} where the run flew {n:,} "
            "a point (shots 0 to n - 1): not one run's files"
        )


def _check_trajectories(folder, fs, root, provenance, points):
    """``_check_of_run`` of trajectories.parquet."""
    with fs.open_input_file(f"{root}/{output.TRAJECTORIES_FILE}") as f:
        metadata = pq.read_metadata(f)
    _check_of_run(folder, output.TRAJECTORIES_FILE, metadata, provenance, points)


def _check_one_run(folder, summary, provenance, shots):
    """RunFolderError unless the shots (``shots``, the Parquet metadata of shots.parquet) are
    the summary's (``_check_of_run``), and as many rows as the summary counts."""
    _check_of_run(folder, output.SHOTS_FILE, shots, provenance, len(summary))
    if "n_shots" in summary and not _counts(summary["n_shots"]):
        raise RunFolderError(f"{folder}: {output.SUMMARY_FILE}'s n_shots holds a value that is "
                             "not a count: not a run's summary")  # fmt: skip
    if "n_shots" in summary and int(summary["n_shots"].sum()) != shots.num_rows:
        raise RunFolderError(
            f"{folder}: {output.SHOTS_FILE} has {shots.num_rows:,} shots where "
            f"{output.SUMMARY_FILE} counts {int(summary['n_shots'].sum()):,}: not one run's files"
        )


def _check_parts(run):
    """RunFolderError unless a dataset run's shots/ holds every part of its plan once (the
    chunks of each point: ceil(n / chunk_size) of them) and no other file that a dataset reader
    would read (a part copied as "part-00014 (1).parquet" was read twice, one missing left its
    shots out, without a word)."""
    p = run.provenance
    if not all(isinstance(p.get(k), int) and p[k] > 0 for k in ("n", "chunk_size")):
        return  # (a damaged provenance: the parts cannot be told; the files are read as they are)
    selector = pafs.FileSelector(f"{run.root}/{output.SHOTS_DIR}", recursive=True)
    found = {}
    for info in run.fs.get_file_info(selector):
        if info.type != pafs.FileType.File or info.base_name.startswith((".", "_")):
            continue  # (what a dataset reader leaves out)
        chunk = output.part_chunk(info.base_name)
        where = info.path.removeprefix(f"{run.root}/")
        if chunk is None:
            raise RunFolderError(f"{run.path}: {where} is not a part of the run (part-NNNNN"
                                 ".parquet), and a dataset reader would read it as shots: remove "
                                 "it")  # fmt: skip
        if chunk in found:
            raise RunFolderError(f"{run.path}: part {chunk} twice: {found[chunk]} and {where}")
        found[chunk] = where
    expected = len(run.summary) * -(-p["n"] // p["chunk_size"])
    missing = sorted(set(range(expected)) - set(found))
    extra = sorted(set(found) - set(range(expected)))
    if missing or extra:
        what = (f"{len(missing)} of its {expected} parts missing (part {missing[0]} the first)"
                if missing else f"a part {extra[0]} beyond its {expected}")  # fmt: skip
        raise RunFolderError(f"{run.path}: {output.SHOTS_DIR}/ has {what}: not a complete run")


def open_run(folder):
    """Open a finished run folder of either layout, a path or an fsspec URL: a ``RunFolder``.

    Raises RunFolderError, one line, when ``folder`` is not a complete run folder or its
    summary or the schema of its shots cannot be read.
    """
    if not isinstance(folder, str | os.PathLike) or "\0" in str(folder):  # (a TypeError)
        raise RunFolderError(f"run folder {shown(folder)}: allowed: a folder's path or a URL")
    try:
        url, fs, root = location.locate(folder)
    except (ImportError, ValueError) as err:  # (a URL whose filesystem is not installed)
        raise RunFolderError(f"{folder}: cannot reach it: {reason_of(err)}") from None
    folder = url or Path(folder)

    def kind(name=None):
        path = root if name is None else f"{root}/{name}"
        try:
            return fs.get_file_info(path).type
        except OSError as err:
            if err.errno is None:
                raise
            # pyarrow's error names no file (a name too long must say which).
            raise OSError(err.errno, os.strerror(err.errno), path) from None

    is_file, is_dir = pafs.FileType.File, pafs.FileType.Directory
    if kind() == pafs.FileType.NotFound:
        raise RunFolderError(f"{folder}: no such run folder")
    if kind() != is_dir:
        raise RunFolderError(f"{folder} is not a folder: give the folder that 'mcrun run' wrote")
    if kind(output.SHOTS_FILE) == is_file:
        layout, trajectories = FILE_LAYOUT, kind(output.TRAJECTORIES_FILE) == is_file
    elif kind(output.SHOTS_DIR) == is_dir or kind(output.SUCCESS_FILE) == is_file:
        if kind(output.SUCCESS_FILE) != is_file:
            raise RunFolderError(f"{folder}: not a complete Dask run (no {output.SUCCESS_FILE})")
        layout, trajectories = DATASET_LAYOUT, kind(output.TRAJECTORIES_DIR) == is_dir
    else:
        raise RunFolderError(
            f"{folder} is not an mcrun run folder: it has no {output.SHOTS_FILE} (nor a "
            f"{output.SHOTS_DIR}/ dataset; write one with 'mcrun run')"
        )
    if kind(output.SUMMARY_FILE) != is_file:
        raise RunFolderError(
            f"{folder} is not an mcrun run folder: it has no {output.SUMMARY_FILE} (write one "
            "with 'mcrun run')"
        )
    reading = output.SUMMARY_FILE  # (the file a damaged run's message names)
    try:
        summary = pd.read_parquet(_source(url, root, output.SUMMARY_FILE))
        with fs.open_input_file(f"{root}/{output.SUMMARY_FILE}") as f:
            provenance = output.decode_provenance(pq.read_metadata(f).metadata)
        shots = None  # shots.parquet's footer: its columns, rows and provenance
        if layout == FILE_LAYOUT:
            reading = output.SHOTS_FILE
            with fs.open_input_file(f"{root}/{output.SHOTS_FILE}") as f:
                shots = pq.read_metadata(f)
            shot_columns = list(shots.schema.to_arrow_schema().names)
        else:
            reading = f"{output.SHOTS_DIR}/"
            shot_columns = _dataset_columns(fs, root)
    except (OSError, pa.ArrowException, ValueError) as err:
        raise RunFolderError(
            f"cannot read the run in {folder}: {reading}: {reason_of(err)}"
        ) from None
    version = provenance.get("format_version", 1)
    if not isinstance(version, int) or isinstance(version, bool):
        raise RunFolderError(f"{folder}: format_version {version!r} is not a format's number "
                             f"(this mcrun writes {output.FORMAT_VERSION}): a damaged "
                             "provenance")  # fmt: skip
    if version != output.FORMAT_VERSION:  # (a later mcrun's files, or a damaged one)
        raise RunFolderError(
            f"{folder}: format_version {version!r}: this mcrun reads runs of format "
            f"{output.FORMAT_VERSION} (a later mcrun wrote it?)"
        )
    if shots is not None:
        _check_one_run(folder, summary, provenance, shots)
        if trajectories:
            reading = output.TRAJECTORIES_FILE
            try:
                _check_trajectories(folder, fs, root, provenance, len(summary))
            except (OSError, pa.ArrowException, ValueError) as err:
                if isinstance(err, RunFolderError):
                    raise
                raise RunFolderError(
                    f"cannot read the run in {folder}: {reading}: {reason_of(err)}"
                ) from None
    run = RunFolder(folder, url, fs, root, layout, summary, provenance, shot_columns, trajectories)
    if layout == DATASET_LAYOUT:
        _check_parts(run)
    return run


def read_shots(folder, columns=None):
    """The shots of a run folder (``RunFolder.shots``)."""
    return open_run(folder).shots(columns)


def read_trajectories(folder):
    """The trajectories of a run folder (``RunFolder.trajectories``), None when it has none."""
    return open_run(folder).trajectories()
