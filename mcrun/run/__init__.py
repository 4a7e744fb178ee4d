"""Runs of many shots: scenarios, the sampler, the plan of a run (chunks, seeds, provenance,
summary rows) and its executors (local threads, Dask), and the replay of launch files."""
