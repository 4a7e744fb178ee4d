"""Writing a run to Parquet: shots, summary and trajectories, with their provenance, atomically.

A run is a folder:

- ``shots.parquet``: one row per shot, written as the run goes (one row group per chunk; LZ4
  where it shrinks a column, ``column_compression``):
  point, group, label, shot (the global sample index i), the sampled inputs, every field of
  ``schema.OUTCOME_FIELDS`` (status as an int8 code, bounces as a nullable int32, the rest
  float64, NaN where a failed shot did not get that far) and status_name. The outcome's
  launch_angle_deg is the sampled column of that name (the same launch, not written twice).
  (The Dask backend, ``mcrun.run.distributed``, writes the same rows as a dataset of parts
  instead, ``shots/part-NNNNN.parquet``, one per chunk, with a ``_SUCCESS`` marker.)
- ``summary.parquet``: one row per point (``stats.summarise``).
- ``trajectories.parquet`` (optional): long format, one row per point of the path of every k-th
  shot: point, shot, t_s, x_m, y_m (positive right), z_m, phase.

Provenance: every file's Parquet key-value metadata (what DuckDB's ``parquet_kv_metadata`` and
``pyarrow.parquet.read_metadata(path).metadata`` show) holds ``mcrun.*`` keys: the scenario
text, path and question, seed, N, point labels, versions, models, the run's geometry (the
frame, tee, pin, aim and targets; in summary.parquet also the hole's map:
``mcrun.results.geometry``), start time, elapsed time, threads, chunk size and backend.
``read_provenance`` decodes them. ``mcrun.elapsed_s`` is the time from the start of the run to
the completion of that file.

Atomicity: ``AtomicFolder`` and ``AtomicFile`` write under a hidden temporary name beside the
destination (``.NAME.partial-HOST-PID-TOKEN``) and rename it into place only when everything is
written; on an error or an interrupt the temporary files are removed, so a folder or file with
the final name is always complete. A destination the rename could not replace (a mount point,
an immutable folder) is refused before anything is written; should the rename still fail, the
finished output is moved into an empty destination folder or kept beside it (``OutputKept``).
What a killed process left, the next one removes (``remove_stale``).
"""

import contextlib
import errno
import json
import os
import platform
import re
import secrets
import shutil
import socket
import stat
import struct
import sys
import tempfile
import time
import tomllib
from pathlib import Path

import numba
import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq

import mcrun
from mcrun.engine.schema import OUTCOME_DTYPES, OUTCOME_FIELDS, PLANE_FIELDS, encode_outcomes
from mcrun.quantities import InputError
from mcrun.results import on_hole as on_hole_columns
from mcrun.status import NAMES as STATUS_NAMES
from mcrun.trajectory import PHASE_NAMES

SHOTS_FILE = "shots.parquet"
SUMMARY_FILE = "summary.parquet"
TRAJECTORIES_FILE = "trajectories.parquet"
RUN_FILES = (SHOTS_FILE, SUMMARY_FILE, TRAJECTORIES_FILE)
# A Dask run's dataset layout: the folders of its parts and its marker of completion.
SHOTS_DIR = "shots"
TRAJECTORIES_DIR = "trajectories"
SUCCESS_FILE = "_SUCCESS"
# What mcrun puts in a run folder besides the run: `mcrun plot`'s and `mcrun report`'s defaults.
PLOTS_FOLDER = "plots"
# The names ``mcrun plot`` writes into a run's plots/ (``report.plots.figures``, and the hole's
# map of ``report.hole_plots``; a picture's temporary name, left by a plot killed): a file of
# another name there is the user's.
PLOT_NAME = re.compile(
    r"\.?(summary|finish|point\d+-(positions|distances|trajectories|hole))"
    r"\.png(\.partial-.+)?"
)
REPORT_FILE = "report.html"
# A report's temporary name while ``mcrun report`` writes it (``AtomicFile``): the run's too.
REPORT_PARTIAL = re.compile(r"\.report\.html\.partial-.+")
# Every name a run folder may hold: what --force replaces, and nothing else.
RUN_FOLDER_NAMES = (*RUN_FILES, SHOTS_DIR, TRAJECTORIES_DIR, SUCCESS_FILE, PLOTS_FOLDER,
                    REPORT_FILE)  # fmt: skip
_PART = re.compile(r"part-(\d+)\.parquet")
# Parquet's codec: LZ4 (LZ4_RAW in the file; pandas, polars, DuckDB and Spark read it). Measured
# on pga-driver and par3-over-water (2-core AMD EPYC): zstd at its default level took 0.57 us a
# shot to encode and write against LZ4's 0.35 (zstd's write was a third to a half of all a run
# did besides the kernel), for files 11 % smaller (156 against 175 B a shot for pga-driver).
# Recompress a run kept for long with any Parquet tool (DuckDB: COPY ... (COMPRESSION zstd)).
COMPRESSION = "lz4"
# A column of numbers that COMPRESSION shrinks by less than this share is written uncompressed:
# a sampled input or an outcome, float64 whose low bytes are as good as random (LZ4 kept 8.03 of
# every 8 bytes of them), or a longitude or latitude (0.99 and 0.91 of them, for 0.02 us a shot
# of the two together). Half of a run's columns are such: CPU to encode and write 1,000,000 shots,
# 0.17-0.18 against 0.18-0.20 us a shot for pga-driver, 0.22 against 0.27 for par3-over-water.
INCOMPRESSIBLE_GAIN = 0.10
# The values of each column that ``column_compression`` tries (its first ones): 128 kB of
# float64, past LZ4's mode for inputs up to 64 kB, which shrinks such data more than it does
# Parquet's pages of up to 1 MB (a latitude to 0.82 of its bytes in 64 kB, 0.91 in 128 kB).
COMPRESSION_SAMPLE = 16384
# Values handed to each column's encoder at a time (pyarrow's default: 1,024): a chunk's column
# in one go writes shots.parquet in about a tenth less time (par3-over-water 0.30-0.31 against
# 0.33-0.41 us a shot, pga-driver 0.22-0.27 against 0.26-0.29), the same values, in pages of up
# to 1 MB as before (65,536 float64 are 512 kB).
WRITE_BATCH_SIZE = 65_536
# The columns of shots.parquet whose row groups carry min/max statistics, for readers that
# skip row groups by point or status. An outcome's row group spans its whole spread, so its
# statistics would skip nothing, and they cost a fifth of the write.
STATISTICS_COLUMNS = ("point", "group", "label", "shot", "status", "status_name")
PREFIX = "mcrun."
# The layout of a run's files, in their provenance: what this mcrun writes and reads.
FORMAT_VERSION = 1

# How each provenance value is stored: text as is, everything else as JSON.
_TEXT_FIELDS = ("scenario_text", "scenario_path", "scenario_name", "start_time_utc", "backend")

_STATUS_DICTIONARY = pa.array([STATUS_NAMES[k] for k in sorted(STATUS_NAMES)])
_PHASE_DICTIONARY = pa.array(list(PHASE_NAMES))


class OutputError(InputError):
    """An output the user asked for cannot be written; the message is one line."""


def writable_folder(out_dir, option="-o"):
    """``out_dir`` (a Path), made if missing, where a file can be written: a temporary file of
    a name of its own is made there and removed (none of the user's is touched); OutputError
    (one line, naming ``option``) otherwise. A name too long is raised as it is, for the command
    line's one line for every path too long."""
    out_dir = Path(out_dir)
    try:
        out_dir.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryFile(dir=out_dir):
            pass
    except OSError as err:
        if err.errno == errno.ENAMETOOLONG:
            raise
        reason = err.strerror or str(err)
        raise OutputError(f"{option}: cannot write to {out_dir}: {reason}") from None
    return out_dir


def part_name(chunk):
    """The file name of chunk ``chunk``'s part in a dataset: ``part-NNNNN.parquet``."""
    return f"part-{chunk:05d}.parquet"


def part_chunk(name):
    """The chunk of a part from its file name (``part_name``'s inverse); None for another file."""
    match = _PART.fullmatch(name)
    return None if match is None else int(match[1])


def versions():
    """Versions of the software that produced a run."""
    return {
        "mcrun": mcrun.__version__,
        "numba": numba.__version__,
        "numpy": np.__version__,
        "pyarrow": pa.__version__,
        "python": platform.python_version(),
    }


def encode_provenance(fields):
    """Parquet key-value metadata (str -> str) from a provenance dict."""
    return {
        PREFIX + k: (str(v) if k in _TEXT_FIELDS else json.dumps(v, allow_nan=True))
        for k, v in fields.items()
    }


def decode_provenance(metadata):
    """The provenance dict back from a file's key-value metadata (bytes or str keys)."""
    fields = {}
    for key, value in (metadata or {}).items():
        key = key.decode() if isinstance(key, bytes) else key
        value = value.decode() if isinstance(value, bytes) else value
        if key.startswith(PREFIX):
            name = key[len(PREFIX) :]
            try:
                fields[name] = value if name in _TEXT_FIELDS else json.loads(value)
            except ValueError:
                raise ValueError(f"its metadata {key} = {value[:40]!r} is not JSON, as mcrun "
                                 "writes it") from None  # fmt: skip
    return fields


def read_provenance(path):
    """The ``mcrun.*`` provenance of a Parquet file written by mcrun."""
    return decode_provenance(pq.read_metadata(path).metadata)


_QUESTION = re.compile(r"^#\s*Question:\s*(.*?)\s*$")


def question_of(provenance):
    """The question a run's scenario answers: its recorded ``question``, else (a run written
    before it was recorded) the one its scenario text asks (``question_in``)."""
    if "question" in provenance:  # (text, as mcrun writes it; anything else says nothing)
        question = provenance["question"]
        return question if isinstance(question, str) else ""
    return question_in(provenance.get("scenario_text") or "")


def question_in(text):
    """The question the scenario ``text`` answers: its ``[scenario] question``, else its first
    ``# Question:`` comment line, else "" (the library's list, a scenario's ``load`` and the
    report's title all read it here). The key wins: a comment copied from another scenario
    above an edited key was the question everywhere."""
    try:
        question = tomllib.loads(text).get("scenario", {}).get("question")
    except (tomllib.TOMLDecodeError, AttributeError):
        question = None
    if isinstance(question, str) and question.strip():  # (an empty key: the comment's)
        return question
    for line in text.splitlines():
        match = _QUESTION.match(line.strip())
        if match:
            return match[1]
    return ""


# --- shots -------------------------------------------------------------------------------------


def outcome_columns(input_names, on_hole=False):
    """The outcome fields shots.parquet holds: all of ``OUTCOME_FIELDS`` (on a Plane, but
    ``HOLE_FIELDS``) but those a sampled input column already holds under the same name
    (launch_angle_deg)."""
    fields = OUTCOME_FIELDS if on_hole else PLANE_FIELDS
    return tuple(name for name in fields if name not in set(input_names))


def shots_schema(input_names, input_types=None, metadata=None, on_hole=False):
    """Arrow schema of shots.parquet for the given sampled input columns.

    ``input_types``: Arrow type per input name (default float64); ``on_hole``: a run on a
    hole, whose shots have ``HOLE_FIELDS`` and ``on_hole.COLUMNS`` too (True), or the Hole
    itself, whose shots have ``on_hole.columns_of(hole)``.

    A column that never holds a null is declared so (not nullable: Parquet's REQUIRED, which
    the writer encodes without definition levels, about a quarter of its time): the shot's
    point, group, label, number and status, and every float64 column, whose missing values are
    NaN. A count (bounces: null where a shot did not get that far), a zone (null off the map)
    and a sampled column of another type (null where a point lacks it) may hold nulls.
    """
    input_types = input_types or {}
    fields = [
        pa.field("point", pa.int32(), nullable=False),
        pa.field("group", pa.dictionary(pa.int32(), pa.string()), nullable=False),
        pa.field("label", pa.dictionary(pa.int32(), pa.string()), nullable=False),
        pa.field("shot", pa.int64(), nullable=False),
    ]
    fields += [_field(name, input_types.get(name, pa.float64())) for name in input_names]
    for name in outcome_columns(input_names, on_hole):
        dtype = np.dtype(OUTCOME_DTYPES.get(name, np.float64))
        fields.append(_field(name, pa.from_numpy_dtype(dtype)))
    fields.append(pa.field("status_name", pa.dictionary(pa.int32(), pa.string()), nullable=False))
    if on_hole is not False and on_hole is not None:
        added = on_hole_columns.COLUMNS if on_hole is True else on_hole_columns.columns_of(on_hole)
        fields += [_field(name, kind) for name, kind in added.items()]
    return pa.schema(fields, metadata=metadata)


def _field(name, kind):
    """A field of shots.parquet: not nullable where it is float64 (``shots_schema``)."""
    return pa.field(name, kind, nullable=kind != pa.float64())


class _ParquetWriter:
    """What the writers below share: closing the file with the run's metadata, or dropping it."""

    _writer = None

    def close(self, extra_metadata=None):
        if self._writer is None:
            return
        if extra_metadata:
            self._writer.add_key_value_metadata(extra_metadata)
        self._writer.close()
        self._writer = None

    def abort(self):
        """Close without caring about the file (it is about to be removed)."""
        if self._writer is not None:
            try:
                self._writer.close()
            finally:
                self._writer = None


# Chunks smaller than this share a row group (a sweep of many small points): a row group costs
# about 3 ms to write and 0.8 kB of footer per column, however few its rows.
ROW_GROUP_ROWS = 65536


class ShotsWriter(_ParquetWriter):
    """shots.parquet: a row group per chunk of ROW_GROUP_ROWS shots or more; smaller chunks are
    kept until together they are that many, and share one (their points in order).

    ``groups`` and ``labels``: the group name and label of every point (by point index);
    ``input_names``: the sampled columns (a point that lacks one gets NaN); ``input_types``:
    their Arrow types (default float64). With ``path`` None nothing is opened: ``table`` then
    builds the chunks' tables for a writer elsewhere (the parts of ``mcrun.run.distributed``).
    ``hole``: the ``Hole`` the shots were played on (None: a plane), for its columns;
    ``starts_xy_m``: where each point's shots were struck on it ((x, y) m; default the tee);
    ``putting``: the green's expected-putts map where the hole's putting is physics (prepared
    by the run layer, ``putting.on_hole.map_of_hole``).
    """

    def __init__(self, path, input_names, groups, labels, metadata, input_types=None, hole=None,
                 starts_xy_m=None, putting=None):  # fmt: skip
        self.path = None if path is None else Path(path)
        self.input_names = tuple(input_names)
        self.input_types = {n: (input_types or {}).get(n, pa.float64()) for n in input_names}
        self.hole = hole
        self.putting = putting
        self.starts_xy_m = [on_hole_columns.TEE] * len(groups) if starts_xy_m is None else [
            tuple(xy) for xy in starts_xy_m
        ]  # fmt: skip
        self._outcomes = outcome_columns(self.input_types, hole is not None)
        group_index = {g: k for k, g in enumerate(dict.fromkeys(groups))}
        self._group_dictionary = pa.array(list(group_index), pa.string())
        self._group_index = [group_index[g] for g in groups]
        self._label_dictionary = pa.array(list(labels), pa.string())
        self.schema = shots_schema(self.input_names, self.input_types, metadata,
                                   False if hole is None else hole)  # fmt: skip
        self.row_groups = {}  # point -> list of the row groups that hold its shots
        self._n_row_groups = 0
        self._pending = []  # (point, table) of the chunks not written yet
        self._pending_rows = 0
        self._writer = None  # opened on the first row group, whose values choose the codecs
        self._ended = self.path is None  # closed or aborted (or nothing to write)

    def _open(self, table=None):
        """Open shots.parquet, each column's codec chosen on ``table``, its first row group
        (``column_compression``; without one, COMPRESSION for every column)."""
        self._writer = pq.ParquetWriter(
            self.path,
            self.schema,
            compression=COMPRESSION if table is None else column_compression(table),
            write_batch_size=WRITE_BATCH_SIZE,
            use_dictionary=dictionary_columns(self.schema),
            write_statistics=[c for c in STATISTICS_COLUMNS if c in self.schema.names],
        )

    def hole_columns(self, point, outcomes):
        """The columns the hole adds to the shots ``outcomes`` of ``point``
        (``on_hole.shot_columns``); None on a plane."""
        if self.hole is None:
            return None
        return on_hole_columns.shot_columns(
            self.hole, outcomes, {"putting": self.putting}, self.starts_xy_m[point]
        )

    def append(self, point, table):
        """Append the chunk of ``point`` made into its ``table`` (``table``: it may hold the
        chunk's outcomes without a copy, so they are not reused until it is written)."""
        self._pending.append((point, table))
        self._pending_rows += table.num_rows
        if self._pending_rows >= ROW_GROUP_ROWS:
            self._flush()

    def _flush(self):
        """Write the chunks kept so far as one row group."""
        if not self._pending:
            return
        table = pa.concat_tables([table for _, table in self._pending])
        if self._writer is None:
            self._open(table)
        self._writer.write_table(table, row_group_size=max(table.num_rows, 1))
        for point in dict.fromkeys(point for point, _ in self._pending):
            self.row_groups.setdefault(point, []).append(self._n_row_groups)
        self._n_row_groups += 1
        self._pending = []
        self._pending_rows = 0

    def close(self, extra_metadata=None):
        if not self._ended:
            self._ended = True
            self._flush()
            if self._writer is None:  # no shot: the schema alone
                self._open()
        super().close(extra_metadata)

    def abort(self):
        self._ended = True
        super().abort()

    def table(self, point, start, sampled, outcomes, hole_columns=None):
        """The chunk of ``point`` with shots start.. as an Arrow table of ``self.schema``
        (``hole_columns``: the hole's, when already made)."""
        m = outcomes.shape[0]
        columns = [
            pa.array(np.full(m, point, dtype=np.int32)),
            pa.DictionaryArray.from_arrays(
                pa.array(np.full(m, self._group_index[point], dtype=np.int32)),
                self._group_dictionary,
            ),
            pa.DictionaryArray.from_arrays(
                pa.array(np.full(m, point, dtype=np.int32)), self._label_dictionary
            ),
            pa.array(np.arange(start, start + m, dtype=np.int64)),
        ]
        for name, kind in self.input_types.items():
            values = sampled.get(name)
            if values is None:
                missing = (
                    pa.array(np.full(m, np.nan)) if kind == pa.float64() else pa.nulls(m, kind)
                )
                columns.append(missing)
            else:
                dtype = kind.to_pandas_dtype()
                columns.append(pa.array(np.broadcast_to(np.asarray(values, dtype=dtype), (m,))))
        encoded = encode_outcomes(outcomes, dict.fromkeys((*self._outcomes, "status")))
        for name in self._outcomes:
            values, missing = encoded[name]
            columns.append(pa.array(values, mask=missing))
        codes = encoded["status"][0]
        columns.append(
            pa.DictionaryArray.from_arrays(pa.array(codes.astype(np.int32)), _STATUS_DICTIONARY)
        )
        if self.hole is not None:
            if hole_columns is None:
                hole_columns = self.hole_columns(point, outcomes)
            columns += hole_columns.values()
        return pa.Table.from_arrays(columns, schema=self.schema)


# --- trajectories ------------------------------------------------------------------------------

TRAJECTORY_SCHEMA = pa.schema(
    [
        pa.field("point", pa.int32()),
        pa.field("shot", pa.int64()),
        pa.field("t_s", pa.float64()),
        pa.field("x_m", pa.float64()),
        pa.field("y_m", pa.float64()),
        pa.field("z_m", pa.float64()),
        pa.field("phase", pa.dictionary(pa.int32(), pa.string())),
    ]
)


class TrajectoryWriter(_ParquetWriter):
    """trajectories.parquet: the paths of the shots given to ``add``, written per chunk."""

    def __init__(self, path, metadata):
        self.path = Path(path)
        self.schema = TRAJECTORY_SCHEMA.with_metadata(metadata)
        self._writer = pq.ParquetWriter(self.path, self.schema, compression=COMPRESSION)
        self._parts = []

    def add(self, point, shot, traj):
        """Buffer one shot's path, ``traj`` (n, 5): t, x, y, z, phase code."""
        self._parts.append((point, shot, np.array(traj, dtype=float)))

    def flush(self):
        if not self._parts:
            return
        self._writer.write_table(trajectory_table(self._parts, self.schema))
        self._parts = []

    def close(self, extra_metadata=None):
        if self._writer is not None:
            self.flush()
        super().close(extra_metadata)


def trajectory_table(parts, schema=TRAJECTORY_SCHEMA):
    """The Arrow table of paths ``parts``: (point, shot, traj (n, 5)) as ``add`` buffers them."""
    lengths = [len(t) for _, _, t in parts]
    points = np.repeat([p for p, _, _ in parts], lengths).astype(np.int32)
    shots = np.repeat([s for _, s, _ in parts], lengths).astype(np.int64)
    data = np.concatenate([t for _, _, t in parts]) if sum(lengths) else np.empty((0, 5))
    columns = [pa.array(points), pa.array(shots)]
    columns += [pa.array(np.ascontiguousarray(data[:, k])) for k in range(4)]
    columns.append(
        pa.DictionaryArray.from_arrays(pa.array(data[:, 4].astype(np.int32)), _PHASE_DICTIONARY)
    )
    return pa.Table.from_arrays(columns, schema=schema)


# --- small tables ------------------------------------------------------------------------------


def column_compression(table):
    """Each column's codec in a file that ``table`` starts (ParquetWriter's ``compression``):
    COMPRESSION, or "none" for a column of numbers whose first COMPRESSION_SAMPLE values in
    ``table`` COMPRESSION shrinks by less than INCOMPRESSIBLE_GAIN."""
    codec = pa.Codec("lz4_raw")  # what Parquet writes for "lz4": LZ4 blocks, without a frame
    chosen = {}
    for field, column in zip(table.schema, table.columns, strict=True):
        chosen[field.name] = COMPRESSION
        numbers = pa.types.is_floating(field.type) or pa.types.is_integer(field.type)
        if not numbers or column.num_chunks == 0 or len(column.chunk(0)) == 0:
            continue
        sample = column.chunk(0).slice(0, COMPRESSION_SAMPLE)
        width = field.type.bit_width // 8
        values = sample.buffers()[1][sample.offset * width : (sample.offset + len(sample)) * width]
        if codec.compress(values).size > (1.0 - INCOMPRESSIBLE_GAIN) * values.size:
            chosen[field.name] = "none"
    return chosen


def dictionary_columns(schema):
    """The columns worth dictionary-encoding: the text ones. Floats have as many values as
    rows, and trying a dictionary on each costs three times the rest of the write."""
    return [
        f.name
        for f in schema
        if not pa.types.is_floating(f.type) and not pa.types.is_integer(f.type)
    ]


def write_table(path, frame, metadata):
    """Write a pandas DataFrame (or an Arrow table) to Parquet with key-value metadata."""
    table = (
        frame if isinstance(frame, pa.Table) else pa.Table.from_pandas(frame, preserve_index=False)
    )
    table = table.replace_schema_metadata({**(table.schema.metadata or {}), **metadata})
    pq.write_table(table, path, compression=COMPRESSION)


# --- atomic destinations -----------------------------------------------------------------------

# Temporary names say which process wrote them: ".NAME.partial-HOST-PID-TOKEN" (the folder or
# file being written) and ".NAME.old-HOST-PID-TOKEN" (an earlier run being replaced). A process
# stopped by SIGKILL (or a machine that went down) cannot remove them: ``remove_stale`` does,
# at the next run into the same folder, for those of this host whose process is gone.
_TEMPORARY = re.compile(
    r"\.(?P<name>.*)\.(?P<kind>partial|old)-(?P<host>[A-Za-z0-9_-]+)-(?P<pid>\d+)-[0-9a-f]{8}",
    re.DOTALL,
)
_HOST = re.sub(r"[^A-Za-z0-9-]", "_", socket.gethostname().split(".")[0])[:32] or "host"
# What a reader takes for a complete run, moved last when a run is moved file by file.
_WRITTEN_LAST = (SUMMARY_FILE, SUCCESS_FILE)
# Linux's FS_IOC_GETFLAGS, _IOR('f', 1, long), and the attributes that forbid a rename.
_FS_IOC_GETFLAGS = 0x80006601 | (struct.calcsize("l") << 16)
_FS_IMMUTABLE_FL = 0x10
_FS_APPEND_FL = 0x20


class OutputKept(OutputError):
    """The output is complete but could not be moved to where it was asked for; ``kept`` is
    where it is."""

    def __init__(self, message, kept):
        super().__init__(message)
        self.kept = kept


def _reason(err):
    return err.strerror or str(err)


def _temporary(path, kind="partial"):
    """A new hidden name beside ``path`` for this process: ``.NAME.<kind>-HOST-PID-TOKEN``,
    NAME cut so that the whole stays within a name's 255 bytes."""
    suffix = f".{kind}-{_HOST}-{os.getpid()}-{secrets.token_hex(4)}"
    room = 255 - 1 - len(suffix)
    name = os.fsdecode(os.fsencode(path.name)[:room])
    return path.parent / f".{name}{suffix}"


def _alive(pid):
    """Whether a process ``pid`` runs on this machine (one of another user counts)."""
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (OSError, OverflowError):  # another user's process, or not a pid: leave it
        return True
    return True


def remove_stale(folder):
    """Remove the temporary folders and files that mcrun processes of this host left in
    ``folder`` and that are gone (stopped by SIGKILL); return the paths removed.

    Only names of the ``_TEMPORARY`` pattern are considered, only those of this host and of a
    process id that no longer runs, and an ``.old-`` copy of an earlier run only once the run
    that replaced it is in place.
    """
    removed = []
    try:
        entries = list(os.scandir(folder))
    except OSError:
        return removed
    for entry in entries:
        match = _TEMPORARY.fullmatch(entry.name)
        if match is None or match["host"] != _HOST or _alive(int(match["pid"])):
            continue
        if match["kind"] == "old" and not os.path.lexists(os.path.join(folder, match["name"])):
            continue  # stopped between the two renames: this is the only copy of the run
        try:
            if entry.is_dir(follow_symlinks=False):
                shutil.rmtree(entry.path)
            else:
                os.unlink(entry.path)
        except OSError:
            continue
        removed.append(Path(entry.path))
    return removed


def _make_parents(path):
    """Create the missing parent folders of ``path``; return those created, deepest last."""
    created = []
    missing = []
    parent = path.parent
    while not parent.exists():
        missing.append(parent)
        if parent.parent == parent:
            break
        parent = parent.parent
    for folder in reversed(missing):
        try:
            folder.mkdir()
        except FileExistsError:
            continue
        except OSError as err:
            _remove_created(created)
            raise OutputError(f"cannot create the folder {folder}: {_reason(err)}") from None
        created.append(folder)
    return created


def _remove_created(created):
    for folder in reversed(created):
        try:
            folder.rmdir()
        except OSError:
            break


def not_a_run(shown, names, metadata_of, plots_of=None):
    """Why a folder ``shown`` that holds ``names`` (not empty) is not a run that a new run may
    replace, or None: it holds neither a summary.parquet nor a shots.parquet (or shots/) with
    mcrun's provenance (``metadata_of(name)``: a file's key-value metadata; OSError or an Arrow
    error where it cannot be read), or it holds a name no run writes (RUN_FOLDER_NAMES, or a
    report being written: REPORT_PARTIAL), or its
    plots/ (``plots_of()``: the names in it) one that ``mcrun plot`` does not (``PLOT_NAME``),
    which replacing the run would delete."""
    foreign = sorted(
        n for n in set(names) - set(RUN_FOLDER_NAMES) if not REPORT_PARTIAL.fullmatch(n)
    )
    if not foreign and PLOTS_FOLDER in names and plots_of is not None:
        foreign = sorted(f"{PLOTS_FOLDER}/{name}" for name in plots_of()
                         if not PLOT_NAME.fullmatch(name))  # fmt: skip
    if foreign:
        more = f" (and {len(foreign) - 1} more)" if len(foreign) > 1 else ""
        return (f"the output folder {shown} holds {foreign[0]!r}{more}, which no run writes: a "
                "run replaces only a run folder's own files: move it, or choose another "
                "folder with -o")  # fmt: skip
    for name in (SUMMARY_FILE, SHOTS_FILE):
        if name in names:
            try:
                metadata = metadata_of(name) or {}
            except (OSError, pa.ArrowException):
                metadata = {}
            if any((k.decode() if isinstance(k, bytes) else k).startswith(PREFIX)
                   for k in metadata):  # fmt: skip
                return None
    if SUCCESS_FILE in names and SHOTS_DIR in names:  # a Dask run whose summary is gone
        return None
    return (f"the output folder {shown} exists and is not an mcrun run folder (no "
            f"{SUMMARY_FILE} that mcrun wrote): choose another with -o")  # fmt: skip


def _names_in(folder):
    """The names in ``folder`` ([] where it is not a folder)."""
    return [entry.name for entry in folder.iterdir()] if folder.is_dir() else []


def _local_metadata(path):
    return lambda name: pq.read_metadata(path / name).metadata


def _immutable(path):
    """Whether ``path`` has Linux's immutable or append-only attribute (``chattr +i``, ``+a``),
    which forbid renaming or removing it; False where that cannot be told."""
    if not sys.platform.startswith("linux"):
        return False
    try:
        import fcntl

        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_NOFOLLOW)
    except (ImportError, OSError):
        return False
    try:
        flags = fcntl.ioctl(fd, _FS_IOC_GETFLAGS, bytes(8))
    except OSError:  # a filesystem without these attributes (tmpfs, NFS, ...)
        return False
    finally:
        os.close(fd)
    return bool(int.from_bytes(flags[:4], sys.byteorder) & (_FS_IMMUTABLE_FL | _FS_APPEND_FL))


def _check_replaceable(path):
    """Refuse, before anything is written, an existing destination that the final rename
    could not replace."""
    if os.path.ismount(path):
        raise OutputError(
            f"the output {path} is a mount point, which a run cannot replace: write into a "
            f"folder inside it (-o {path / 'run'})"
        )
    if _immutable(path):
        raise OutputError(
            f"the output {path} is immutable or append-only (chattr +i or +a): a run cannot "
            "replace it; choose another with -o"
        )
    parent = os.stat(path.parent)
    if parent.st_mode & stat.S_ISVTX and os.geteuid() not in (
        0,
        parent.st_uid,
        os.lstat(path).st_uid,
    ):
        raise OutputError(
            f"the output {path} belongs to another user in a folder with the sticky bit "
            f"({path.parent}): a run cannot replace it; choose another with -o"
        )


def _move(source, destination):
    try:
        os.rename(source, destination)
    except OSError as err:
        if err.errno != errno.EXDEV:
            raise
        shutil.move(source, destination)  # another filesystem (a bind mount): copy


def _move_into(tmp, path):
    """Move what ``tmp`` holds into the empty folder ``path``, the summary and the success
    marker last; on a failure move back what was moved and return False."""
    names = sorted(
        os.listdir(tmp),
        key=lambda n: _WRITTEN_LAST.index(n) + 1 if n in _WRITTEN_LAST else 0,
    )
    moved = []
    try:
        for name in names:
            _move(tmp / name, path / name)
            moved.append(name)
    except OSError:
        for name in reversed(moved):
            with contextlib.suppress(OSError):
                _move(path / name, tmp / name)
        return False
    with contextlib.suppress(OSError):
        tmp.rmdir()
    return True


def _keep(tmp, path):
    """Give the finished ``tmp`` a visible name beside ``path``, ``NAME.complete-<time>``
    (``STEM.complete-<time>.SUFFIX`` for a file); return where it is."""
    stamp = time.strftime("%Y%m%d-%H%M%S")
    stem, suffix = (path.name, "") if tmp.is_dir() else (path.stem, path.suffix)
    for k in range(100):
        tag = f".complete-{stamp}" + (f"-{k}" if k else "") + suffix
        room = 255 - len(os.fsencode(tag))
        kept = path.parent / (os.fsdecode(os.fsencode(stem)[:room]) + tag)
        if os.path.lexists(kept):
            continue
        try:
            os.rename(tmp, kept)
        except OSError:
            break
        return kept
    return tmp


class AtomicFolder:
    """A run folder written under a temporary name and renamed into place on ``commit``.

    Refuses (OutputError, before anything is written) a destination that is a file, a
    non-empty folder that is not a run folder, or a run folder unless ``force``, and one the
    final rename could not replace (a mount point, an immutable folder); with ``force`` the
    old run is replaced only once the new one is complete. Removes what killed runs left
    beside it (``remove_stale``). A finished run is never lost to the final rename: see
    ``commit``.
    """

    def __init__(self, path, force=False):
        self.path = Path(path)
        self.force = force
        self.tmp = None
        self._created = []
        self._committed = False

    def __enter__(self):
        path = self.path
        if path.exists() or path.is_symlink():
            if not path.is_dir():
                raise OutputError(f"the output {path} exists and is not a folder")
            names = [entry.name for entry in path.iterdir()]
            if names:
                problem = not_a_run(path, names, _local_metadata(path),
                                    lambda: _names_in(path / PLOTS_FOLDER))  # fmt: skip
                if problem is not None:
                    raise OutputError(problem)
                if not self.force:
                    raise OutputError(
                        f"the output folder {path} already holds a run: use --force "
                        "(force=True) to replace it, or choose another with -o (out_dir)"
                    )
            _check_replaceable(path)
        self._created = _make_parents(path)
        remove_stale(path.parent)
        self.tmp = _temporary(path)
        try:
            self.tmp.mkdir()
        except OSError as err:
            _remove_created(self._created)
            raise OutputError(f"cannot write in the folder {path.parent}: {_reason(err)}") from None
        return self

    def file(self, name):
        return self.tmp / name

    def commit(self):
        """Rename the finished folder into place (replacing an earlier run). Should that fail
        (a busy or immutable destination), the run is moved file by file into the destination
        when that is an empty folder, else kept beside it as ``NAME.complete-<time>`` and
        ``OutputKept`` says where."""
        try:
            self._replace()
        except OSError as err:
            self._committed = True  # from here on the temporary folder is a finished run
            path = self.path
            if path.is_dir() and not path.is_symlink() and not any(path.iterdir()):
                if _move_into(self.tmp, path):
                    return
            kept = _keep(self.tmp, path)
            raise OutputKept(
                f"the run is complete but could not be moved to {path}: {_reason(err)}; "
                f"it is in {kept}",
                kept,
            ) from None

    def _replace(self):
        path = self.path
        old = None
        if path.exists() and not (path.is_dir() and not any(path.iterdir())):
            if not self.force:  # (checked before the run; another finished there meanwhile)
                why = "another run was written there meanwhile (without --force it stays)"
                raise FileExistsError(errno.EEXIST, why, str(path))
            old = _temporary(path, "old")  # an empty folder the rename replaces by itself
            os.rename(path, old)
        try:
            os.rename(self.tmp, path)
        except OSError:
            if old is not None:
                os.rename(old, path)
            raise
        self._committed = True
        if old is not None:
            shutil.rmtree(old, ignore_errors=True)

    def __exit__(self, exc_type, exc, tb):
        if not self._committed:
            if self.tmp is not None:
                shutil.rmtree(self.tmp, ignore_errors=True)
            _remove_created(self._created)
        return False


class AtomicFile:
    """One file written under a temporary name beside it and renamed on ``commit``; the same
    checks as ``AtomicFolder``."""

    def __init__(self, path, force=False):
        self.path = Path(path)
        self.force = force
        self.tmp = None
        self._created = []
        self._committed = False

    def __enter__(self):
        path = self.path
        if path.is_dir():
            raise OutputError(f"the output {path} is a folder")
        if path.exists():
            if not self.force:
                raise OutputError(f"the output {path} already exists: use --force to replace it")
            _check_replaceable(path)
        self._created = _make_parents(path)
        remove_stale(path.parent)
        self.tmp = _temporary(path)
        try:
            self.tmp.touch(exist_ok=False)
        except OSError as err:
            _remove_created(self._created)
            raise OutputError(f"cannot write in the folder {path.parent}: {_reason(err)}") from None
        return self

    def commit(self):
        """Rename the finished file into place; should that fail, it is kept beside the
        destination as ``STEM.complete-<time>.SUFFIX`` and ``OutputKept`` says where."""
        try:
            if not self.force and os.path.lexists(self.path):  # (another wrote it meanwhile)
                why = "another process wrote it meanwhile (without --force it stays)"
                raise FileExistsError(errno.EEXIST, why, str(self.path))
            os.replace(self.tmp, self.path)
        except OSError as err:
            self._committed = True
            kept = _keep(self.tmp, self.path)
            raise OutputKept(
                f"{self.path} is complete but could not be moved into place: {_reason(err)}; "
                f"it is in {kept}",
                kept,
            ) from None
        self._committed = True

    def __exit__(self, exc_type, exc, tb):
        if not self._committed:
            if self.tmp is not None:
                try:
                    self.tmp.unlink()
                except FileNotFoundError:
                    pass
            _remove_created(self._created)
        return False
