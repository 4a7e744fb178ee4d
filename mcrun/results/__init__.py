"""What a run leaves behind: the Parquet writer and its provenance, the dispersion statistics,
and the reader of a run folder, local or Dask."""
