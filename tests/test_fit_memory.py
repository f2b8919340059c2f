"""`spinbounce fit` at cluster scale: bounded memory, the same fit as in memory.

`spinbounce fit` at cluster scale: a sweep's fit in memory bounded independently of its row
count, equal to the in-memory fit.

The dataset is 4,000,000 rows made here in the sweep's own layout (a LAMMPS sweep of that size
takes minutes; what is tested is the fit): final = M @ initial with a 1e-5 scatter, the theory
column the exact matrix. The streamed fit runs in a process of its own whose peak resident
memory is read from the kernel (VmHWM) and must stay under 500 MB; the in-memory fit of
the same rows takes several times that.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from spinbounce.fitting import fit_groups
from spinbounce.model.contact import ContactModel
from spinbounce.records import write_parquet_atomic

ROWS, PER_FILE = 4_000_000, 50_000  # a file a chunk, as sweeps write them (25,000 by default)
LIMIT_MB = 500


def _write_dataset(folder: Path) -> None:
    model = ContactModel()
    matrix = model.matrix()
    rng = np.random.default_rng(7)
    for k in range(ROWS // PER_FILE):
        n = PER_FILE
        initial = np.column_stack([rng.uniform(-1.5, -0.1, n), rng.uniform(-2, 2, n), rng.uniform(-2, 2, n)])
        theory = initial @ matrix.T
        final = theory + rng.normal(0.0, 1e-5, theory.shape)
        columns = {"group": np.zeros(n, dtype=np.int64), "chunk": np.full(n, k), "index": np.arange(k * n, (k + 1) * n)}
        for j, s in enumerate(("v_n", "v_t", "r_omega")):
            columns.update({f"{s}_initial": initial[:, j], f"{s}_lammps": final[:, j], f"{s}_theory": theory[:, j],
                            f"{s}_error": final[:, j] - theory[:, j]})
        columns["error"] = np.abs(final - theory).max(axis=1) / np.linalg.norm(initial, axis=1)
        columns["status"] = np.full(n, "ok", dtype=object)
        for name in ("m", "r", "alpha", "kn", "kt", "gamma_n", "gamma_t"):
            columns[name] = np.full(n, getattr(model, name))
        columns.update(mu=np.full(n, np.nan), limit_damping=np.zeros(n, dtype=bool), normal=np.full(n, "hooke", dtype=object),
                       wall=np.full(n, "granular", dtype=object), dt=np.full(n, 0.005))
        write_parquet_atomic(folder / f"chunk-0000-{k:06d}.parquet", pd.DataFrame(columns))


#: The child's peak resident memory from the kernel's VmHWM (reset by exec, unlike
#: ru_maxrss, which would carry the forking test process's own).
STREAMED = """
import json, sys
from spinbounce.fitting_stream import fit_dataset
fits = fit_dataset(__import__("pathlib").Path(sys.argv[1]))
status = open("/proc/self/status").read().split("VmHWM:")[1].split()
print(json.dumps({"peak_mb": float(status[0]) / 1024, "fits": fits}))
"""


@pytest.mark.slow
def test_fit_of_four_million_rows_stays_under_500_mb_and_equals_the_in_memory_fit(tmp_path):
    chunks = tmp_path / "chunks"
    chunks.mkdir()
    _write_dataset(chunks)
    done = subprocess.run([sys.executable, "-c", STREAMED, str(chunks)], capture_output=True, text=True, check=True)
    report = json.loads(done.stdout)
    assert report["peak_mb"] < LIMIT_MB, report["peak_mb"]
    (streamed,) = report["fits"]
    (in_memory,) = fit_groups(pd.read_parquet(chunks))
    assert streamed["n"] == in_memory["n"] == ROWS
    assert np.abs(np.array(streamed["matrix"]) - np.array(in_memory["matrix"])).max() < 1e-12
    assert streamed["Omega"] == pytest.approx(in_memory["Omega"], abs=1e-12)
    assert streamed["median_deviation"] == in_memory["median_deviation"]
