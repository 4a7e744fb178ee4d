"""Writing a run to Parquet: shots, summary and trajectories, with their provenance, atomically.

A run is a folder:

- ``shots.parquet``: one row per shot, written as the run goes (one row group per chunk, zstd):
  point, group, label, shot (the global sample index i), the sampled inputs, every field of
  ``shot.OUTCOME_FIELDS`` (status as an int8 code, bounces as a nullable int32, the rest
  float64, NaN where a failed shot did not get that far) and status_name. The outcome's
  launch_angle_deg is the sampled column of that name (the same launch, not written twice).
  (The Dask backend, ``mcrun.distributed``, writes the same rows as a dataset of parts
  instead, ``shots/part-NNNNN.parquet``, one per chunk, with a ``_SUCCESS`` marker.)
- ``summary.parquet``: one row per point (``stats.summarise``).
- ``trajectories.parquet`` (optional): long format, one row per point of the path of every k-th
  shot: point, shot, t_s, x_m, y_m (positive right), z_m, phase.

Provenance: every file's Parquet key-value metadata (what DuckDB's ``parquet_kv_metadata`` and
``pyarrow.parquet.read_metadata(path).metadata`` show) holds ``mcrun.*`` keys: the scenario
text and path, seed, N, point labels, versions, models, start time, elapsed time, threads,
chunk size and backend. ``read_provenance`` decodes them. ``mcrun.elapsed_s`` is the time from
the start of the run to the completion of that file.

Atomicity: ``AtomicFolder`` and ``AtomicFile`` write under a hidden temporary name beside the
destination and rename it into place only when everything is written; on an error or an
interrupt the temporary files are removed, so a folder or file with the final name is always
complete.
"""

import json
import os
import platform
import secrets
import shutil
from pathlib import Path

import numba
import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq

import mcrun
from mcrun.api import InputError
from mcrun.shot import OUTCOME_FIELDS
from mcrun.status import NAMES as STATUS_NAMES
from mcrun.trajectory import PHASE_NAMES

SHOTS_FILE = "shots.parquet"
SUMMARY_FILE = "summary.parquet"
TRAJECTORIES_FILE = "trajectories.parquet"
RUN_FILES = (SHOTS_FILE, SUMMARY_FILE, TRAJECTORIES_FILE)
COMPRESSION = "zstd"
# The columns of shots.parquet whose row groups carry min/max statistics, for readers that
# skip row groups by point or status. An outcome's row group spans its whole spread, so its
# statistics would skip nothing, and they cost a fifth of the write.
STATISTICS_COLUMNS = ("point", "group", "label", "shot", "status", "status_name")
PREFIX = "mcrun."

# How each provenance value is stored: text as is, everything else as JSON.
_TEXT_FIELDS = ("scenario_text", "scenario_path", "scenario_name", "start_time_utc", "backend")

_STATUS_DICTIONARY = pa.array([STATUS_NAMES[k] for k in sorted(STATUS_NAMES)])
_PHASE_DICTIONARY = pa.array(list(PHASE_NAMES))
_BOUNCES = OUTCOME_FIELDS.index("bounces")
_STATUS = OUTCOME_FIELDS.index("status")


class OutputError(InputError):
    """An output the user asked for cannot be written; the message is one line."""


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
            fields[name] = value if name in _TEXT_FIELDS else json.loads(value)
    return fields


def read_provenance(path):
    """The ``mcrun.*`` provenance of a Parquet file written by mcrun."""
    return decode_provenance(pq.read_metadata(path).metadata)


# --- shots -------------------------------------------------------------------------------------


def outcome_columns(input_names):
    """The outcome fields shots.parquet holds: all of ``OUTCOME_FIELDS`` but those a sampled
    input column already holds under the same name (launch_angle_deg)."""
    return tuple(name for name in OUTCOME_FIELDS if name not in set(input_names))


def shots_schema(input_names, input_types=None, metadata=None):
    """Arrow schema of shots.parquet for the given sampled input columns.

    ``input_types``: Arrow type per input name (default float64).
    """
    input_types = input_types or {}
    fields = [
        pa.field("point", pa.int32()),
        pa.field("group", pa.dictionary(pa.int32(), pa.string())),
        pa.field("label", pa.dictionary(pa.int32(), pa.string())),
        pa.field("shot", pa.int64()),
    ]
    fields += [pa.field(name, input_types.get(name, pa.float64())) for name in input_names]
    for name in outcome_columns(input_names):
        if name == "bounces":
            fields.append(pa.field(name, pa.int32()))
        elif name == "status":
            fields.append(pa.field(name, pa.int8()))
        else:
            fields.append(pa.field(name, pa.float64()))
    fields.append(pa.field("status_name", pa.dictionary(pa.int32(), pa.string())))
    return pa.schema(fields, metadata=metadata)


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


class ShotsWriter(_ParquetWriter):
    """shots.parquet, one row group per chunk.

    ``groups`` and ``labels``: the group name and label of every point (by point index);
    ``input_names``: the sampled columns (a point that lacks one gets NaN); ``input_types``:
    their Arrow types (default float64). With ``path`` None nothing is opened: ``table`` then
    builds the chunks' tables for a writer elsewhere (the parts of ``mcrun.distributed``).
    """

    def __init__(self, path, input_names, groups, labels, metadata, input_types=None):
        self.path = None if path is None else Path(path)
        self.input_names = tuple(input_names)
        self.input_types = {n: (input_types or {}).get(n, pa.float64()) for n in input_names}
        self._outcomes = [
            (k, name) for k, name in enumerate(OUTCOME_FIELDS) if name not in self.input_types
        ]
        group_index = {g: k for k, g in enumerate(dict.fromkeys(groups))}
        self._group_dictionary = pa.array(list(group_index), pa.string())
        self._group_index = [group_index[g] for g in groups]
        self._label_dictionary = pa.array(list(labels), pa.string())
        self.schema = shots_schema(self.input_names, self.input_types, metadata)
        self.row_groups = {}  # point -> list of row group indices
        self._n_row_groups = 0
        self._writer = None
        if self.path is not None:
            self._writer = pq.ParquetWriter(
                self.path,
                self.schema,
                compression=COMPRESSION,
                use_dictionary=dictionary_columns(self.schema),
                write_statistics=[c for c in STATISTICS_COLUMNS if c in self.schema.names],
            )

    def write(self, point, start, sampled, outcomes):
        """Append the chunk of ``point`` with shots start.. as one row group."""
        table = self.table(point, start, sampled, outcomes)
        self._writer.write_table(table, row_group_size=max(table.num_rows, 1))
        self.row_groups.setdefault(point, []).append(self._n_row_groups)
        self._n_row_groups += 1

    def table(self, point, start, sampled, outcomes):
        """The chunk of ``point`` with shots start.. as an Arrow table of ``self.schema``."""
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
        codes = outcomes[:, _STATUS].astype(np.int8)
        for k, name in self._outcomes:
            column = outcomes[:, k]
            if name == "bounces":
                missing = ~np.isfinite(column)
                columns.append(
                    pa.array(np.where(missing, 0, column).astype(np.int32), mask=missing)
                )
            elif name == "status":
                columns.append(pa.array(codes))
            else:
                columns.append(pa.array(np.ascontiguousarray(column)))
        columns.append(
            pa.DictionaryArray.from_arrays(pa.array(codes.astype(np.int32)), _STATUS_DICTIONARY)
        )
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


def _reason(err):
    return err.strerror or str(err)


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


def _is_run_folder(path):
    return any((path / name).exists() for name in RUN_FILES)


class AtomicFolder:
    """A run folder written under a temporary name and renamed into place on ``commit``.

    Refuses (OutputError, before anything is written) a destination that is a file, a
    non-empty folder that is not a run folder, or a run folder unless ``force``; with
    ``force`` the old run is replaced only once the new one is complete.
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
            if any(path.iterdir()):
                if not _is_run_folder(path):
                    raise OutputError(
                        f"the output folder {path} exists and is not an mcrun run folder: "
                        "choose another with -o"
                    )
                if not self.force:
                    raise OutputError(
                        f"the output folder {path} already holds a run: use --force to "
                        "replace it, or choose another with -o"
                    )
        self._created = _make_parents(path)
        self.tmp = path.parent / f".{path.name}.partial-{secrets.token_hex(4)}"
        try:
            self.tmp.mkdir()
        except OSError as err:
            _remove_created(self._created)
            raise OutputError(f"cannot write in the folder {path.parent}: {_reason(err)}") from None
        return self

    def file(self, name):
        return self.tmp / name

    def commit(self):
        path = self.path
        old = None
        if path.exists():
            old = path.parent / f".{path.name}.old-{secrets.token_hex(4)}"
            os.rename(path, old)
        os.rename(self.tmp, path)
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
    """One file written under a temporary name beside it and renamed on ``commit``."""

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
        if path.exists() and not self.force:
            raise OutputError(f"the output {path} already exists: use --force to replace it")
        self._created = _make_parents(path)
        self.tmp = path.parent / f".{path.name}.partial-{secrets.token_hex(4)}"
        try:
            self.tmp.touch(exist_ok=False)
        except OSError as err:
            _remove_created(self._created)
            raise OutputError(f"cannot write in the folder {path.parent}: {_reason(err)}") from None
        return self

    def commit(self):
        os.replace(self.tmp, self.path)
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
