"""Sweeps: many collisions, in chunks, in parallel, resumable, into one Parquet dataset.

:mod:`.spec` validates a sweep's description (a TOML scene file, or the same from flags;
its keys are in that module's docstring); :mod:`.run` runs its chunks; :mod:`.dataset` reads them.
"""

from .dataset import chunk_files, read_results, status_counts
from .run import chunk_path, chunk_table, run_chunk, run_one_chunk, run_sweep
from .spec import DEFAULT_CHUNK, MODEL_KEYS, SweepError, SweepSpec, load_spec, spec_from_dict

__all__ = ["SweepError", "SweepSpec", "load_spec", "spec_from_dict", "run_sweep", "run_one_chunk", "chunk_table",
           "chunk_path", "chunk_files", "read_results", "run_chunk", "status_counts", "DEFAULT_CHUNK", "MODEL_KEYS"]
