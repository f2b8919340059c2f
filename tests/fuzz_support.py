"""What the fuzz invocations meet and how their results are judged.

The files: each made on demand in the case's own folder.
A case names the files it needs (``Case.files``); :func:`make` writes them before the command
runs, and :func:`snapshot` records every file's bytes so that a refusal can be checked to
have left them all as they were.

The checks of a successful invocation, against the physics, never against the command's own
numbers. The physics used in the checks: an undamped Hookean bounce reverses v_n exactly
and lasts pi sqrt(m/kn) (m the reduced mass, here m); with kt = 0 there is no tangential force;
a gross-slip bounce (Coulomb cap mu reached throughout) changes v_t by -2 mu |v_n| and r omega
by -2 mu |v_n| / alpha; kt/kn = alpha/(1+alpha) gives Omega = -2 (the paper's magic ratio); the
paper's defaults give Omega = -1.28384 (its Fig. 2).
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pandas as pd

#: An earlier run's result, which no refusal may touch.
EARLIER = '{"mine": "an earlier run, not to be lost"}\n'


def _text(name: str, content: str):
    def write(folder: Path) -> None:
        (folder / name).parent.mkdir(parents=True, exist_ok=True)
        (folder / name).write_text(content)
    return write


def _folder(name: str):
    return lambda folder: (folder / name).mkdir(parents=True, exist_ok=True)


def _corrupt_parquet(folder: Path) -> None:
    chunks = folder / "corrupt" / "chunks"
    chunks.mkdir(parents=True)
    (chunks / "chunk-0000-000000.parquet").write_bytes(b"PAR1 this is not a parquet file\x00\x01")


def _random_parquet(folder: Path) -> None:
    """A chunk of random bytes (seeded: the same every run) under a chunk's name."""
    import numpy as np

    chunks = folder / "random" / "chunks"
    chunks.mkdir(parents=True)
    (chunks / "chunk-0000-000000.parquet").write_bytes(np.random.default_rng(16).bytes(4096))


def _foreign_parquet(folder: Path) -> None:
    import pandas as pd

    chunks = folder / "foreign" / "chunks"
    chunks.mkdir(parents=True)
    pd.DataFrame({"city": ["Oslo", "Lima"], "population": [709_000, 10_000_000]}).to_parquet(
        chunks / "chunk-0000-000000.parquet")


def _sweep_record(content: bytes):
    """A sweep's output folder whose sweep.json is ``content`` (truncated, corrupt, foreign, binary)."""
    def write(folder: Path) -> None:
        (folder / "swept" / "chunks").mkdir(parents=True)
        (folder / "swept" / "sweep.json").write_bytes(content)
    return write


def _references(manifest: bytes | None = None, table: bytes | None = None):
    """A copy of the stored references with its manifest or the defaults case's table replaced."""
    def write(folder: Path) -> None:
        import shutil

        shutil.copytree(Path(__file__).parent / "reference", folder / "refs")
        if manifest is not None:
            (folder / "refs" / "MANIFEST.json").write_bytes(manifest)
        if table is not None:
            (folder / "refs" / "defaults.csv").write_bytes(table)
    return write


SCENE_OK = """[model]
mu = 0.3
[states]
n = 10
v_n = [-1.5, -0.1]
v_t = [-2, 2]
r_omega = [-2, 2]
"""

MAKERS = {
    "notes.txt": _text("notes.txt", "the user's notes\n"),
    "folder": _folder("folder"),
    "run": _text("run/result.json", EARLIER),
    "mydeck": _text("mydeck/in.lammps", "# a deck of the user's, not to be lost\n"),
    "figout": _text("figout/notes.txt", "the user's notes\n"),
    "series.csv": _text("series.csv", "t,vt\n0,1\n"),
    "bad.toml": _text("bad.toml", "this is = not [ toml\n"),
    "empty.toml": _text("empty.toml", ""),
    "unknown.toml": _text("unknown.toml", SCENE_OK + "colour = 'red'\n"),
    "typo.toml": _text("typo.toml", SCENE_OK.replace("mu = 0.3", "mu = 0.3\nkn_typo = 5")),
    "words.toml": _text("words.toml", SCENE_OK.replace("mu = 0.3", "mu = 'high'")),
    "negative.toml": _text("negative.toml", SCENE_OK.replace("mu = 0.3", "mu = -0.3")),
    "alpha.toml": _text("alpha.toml", SCENE_OK.replace("mu = 0.3", "alpha = 2.0")),
    "n_text.toml": _text("n_text.toml", SCENE_OK.replace("n = 10", "n = 'ten'")),
    "vn_one.toml": _text("vn_one.toml", SCENE_OK.replace("v_n = [-1.5, -0.1]", "v_n = -1.0")),
    "ok.toml": _text("ok.toml", SCENE_OK),
    "corrupt": _corrupt_parquet,
    "random": _random_parquet,
    "x.parquet": _text("x.parquet", "a note, named like a Parquet file\n"),
    "vn_positive.toml": _text("vn_positive.toml", SCENE_OK.replace("v_n = [-1.5, -0.1]", "v_n = [0.1, 1.5]")),
    "figout-fig2": _text("figout/fig2/notes.txt", "the user's notes\n"),
    "foreign": _foreign_parquet,
    "emptydir": _folder("emptydir"),
    "sweep-truncated": _sweep_record(b'{"scene_hash": "0123'),
    "sweep-binary": _sweep_record(b"\xff\xfe\x00\x01"),
    "sweep-list": _sweep_record(b"[1, 2, 3]"),
    "refs-corrupt-manifest": _references(manifest=b"{not json"),
    "refs-list-manifest": _references(manifest=b"[]"),
    "refs-text-table": _references(table=b"v_n,v_t\n1,x\n"),
    "refs-ragged-table": _references(table=b"v_n,v_t\n1,2,3\n"),
    "user.png": _text("user.png", "the user's own image, not to be lost\n"),
    "bench.json": _text("bench.json", EARLIER),
    "figout-fig2.png": _text("figout/fig2.png", "the user's own image, not to be lost\n"),
}


def make(folder: Path, names) -> None:
    for name in names:
        MAKERS[name](folder)


def snapshot(folder: Path) -> dict[str, bytes]:
    """Every regular file under ``folder`` and its bytes."""
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*"))
            if p.is_file() and not p.is_fifo()}


# -- the physics the successful cases are checked against ------------------------------------

#: LAMMPS against the exact theory: the default step's accuracy is 1e-4 of the state's size;
#: twice that leaves room for the phase of the contact's end within its last step.
LAMMPS_TOLERANCE = 2e-4
#: The theory command's closed forms: a few roundings of double precision.
THEORY_TOLERANCE = 1e-12


def reversed_normal(v_n: float, tolerance: float = THEORY_TOLERANCE):
    """v_n' = -v_n, nothing tangential (an undamped Hookean bounce with no slip)."""
    def check(stdout, folder):
        final = json.loads(stdout)["theory"]
        assert abs(final["v_n"] + v_n) <= tolerance * max(1.0, abs(v_n)), final
        assert abs(final["v_t"]) <= tolerance and abs(final["r_omega"]) <= tolerance, final
    return check


def gross_slip(v_n: float, v_t: float, mu: float, alpha: float = 0.4, tolerance: float = THEORY_TOLERANCE):
    size = math.hypot(v_n, v_t)

    def check(stdout, folder):
        final = json.loads(stdout)["theory"]
        assert abs(final["v_n"] + v_n) <= tolerance * size, final
        assert abs(final["v_t"] - (v_t - 2 * mu * abs(v_n))) <= tolerance * size, final
        assert abs(final["r_omega"] + 2 * mu * abs(v_n) / alpha) <= tolerance * size, final
    return check


def unchanged_tangential(v_n: float, v_t: float, r_omega: float, tolerance: float = THEORY_TOLERANCE):
    """kt = 0 or mu = 0: the wall exerts no tangential force."""
    def check(stdout, folder):
        final = json.loads(stdout)["theory"]
        assert abs(final["v_n"] + v_n) <= tolerance, final
        assert abs(final["v_t"] - v_t) <= tolerance and abs(final["r_omega"] - r_omega) <= tolerance, final
    return check


def paper_bounce(v_t: float, r_omega: float = 0.0, tolerance: float = 1e-4, kt: float = 1.0, kn: float = 10.0,
                 alpha: float = 0.4):
    """LAMMPS's final state at v_n = -1 is Eq. 18's, whatever the size of the slip u = v_t + r omega (the
    matrix is linear): Omega = cos(pi sqrt(kt/kn (1 + alpha)/alpha)) - 1, v_t' = v_t + alpha Omega u/(1 + alpha),
    r omega' = r omega + Omega u/(1 + alpha); within the default accuracy of the state's size."""
    omega, slip = math.cos(math.pi * math.sqrt(kt / kn * (1 + alpha) / alpha)) - 1.0, v_t + r_omega

    def check(stdout, folder):
        final, size = json.loads(stdout)["lammps"], math.sqrt(1.0 + v_t**2 + r_omega**2)
        assert abs(final["v_n"] - 1.0) <= tolerance * size, final
        assert abs(final["v_t"] - (v_t + alpha * omega * slip / (1 + alpha))) <= tolerance * size, final
        assert abs(final["r_omega"] - (r_omega + omega * slip / (1 + alpha))) <= tolerance * size, final
    return check


def omega_is(expected: float, tolerance: float = 1e-6):
    def check(stdout, folder):
        assert abs(json.loads(stdout)["Omega"] - expected) <= tolerance, stdout
    return check


def contact_time(m: float, kn: float):
    def check(stdout, folder):
        assert abs(json.loads(stdout)["contact_time"] - math.pi * math.sqrt(m / kn)) <= 1e-12, stdout
    return check


def initial_is(**values):
    def check(stdout, folder):
        initial = json.loads(stdout)["initial"]
        for key, value in values.items():
            assert initial[key] == value, initial
    return check


def pair_meets_its_reference(moved: str):
    """A pair run: LAMMPS within the default accuracy of the pair's exact reference, status ok, and the
    row ``moved`` changed by the contact (the part of the motion the case is about)."""
    def check(stdout, folder):
        error = re.search(r"max \|LAMMPS - theory\| / the pair's speed = (\S+) \(theory: the exact reference; "
                          r"status ok\)", stdout)
        assert error and float(error.group(1)) <= LAMMPS_TOLERANCE, stdout
        row = next(line.split() for line in stdout.splitlines() if line.split()[:1] == [moved])
        assert abs(float(row[3]) - float(row[1])) > 1e-3, stdout  # theory (the exact reference) against initial
    return check


def printed(*needles: str):
    def check(stdout, folder):
        assert all(needle in stdout for needle in needles), stdout
    return check


def calibrated(e: float, time: float, m: float = 1.0):
    """A damped linear bounce: e = exp(-gamma_n t_c / 2m), t_c = pi / sqrt(kn/m - (gamma_n/2m)^2)."""
    def check(stdout, folder):
        got = json.loads(stdout)["parameters"]
        gamma_n = -2.0 * m * math.log(e) / time
        assert math.isclose(got["gamma_n"], gamma_n, rel_tol=1e-12), got
        assert math.isclose(got["kn"], m * ((math.pi / time) ** 2 + (gamma_n / (2 * m)) ** 2), rel_tol=1e-12), got
    return check


def chunks_listed(n: int):
    def check(stdout, folder):
        chunks = json.loads(stdout)
        assert sum(c["stop"] - c["start"] for c in chunks) == n, chunks[:3]
        assert not any(folder.glob("*/chunks/*.parquet")), "listing ran a chunk"
    return check


def figure_beside_user_file(name: str, out: str = "spinbounce-figures"):
    """The figure goes to ``out`` (by default the studies' own folder), within the default
    accuracy of the exact theory; the user's file in figout/ stays as it was."""
    def check(stdout, folder):
        assert json.loads((folder / out / f"{name}.json").read_text())["max_deviation_exact"] < 1e-4
        assert (folder / "figout" / "notes.txt").read_text() == "the user's notes\n"
    return check


def capped_frozen(mu: float, overlap: float, kn: float = 10.0, m: float = 1.0, alpha: float = 0.4):
    """Held under a cap mu kn overlap: every force moves v_t and r omega as alpha : 1 (Eq. 13), and
    the slip u = v_t + r omega changes no faster than the cap allows, (1 + alpha)/(alpha m) mu F_n,
    which is reached (the spring alone would exceed it here)."""
    def check(stdout, folder):
        table = pd.read_csv(folder / "f" / "frozen.csv")
        v_t, r_omega = table["v_t"].to_numpy(), table["r_omega"].to_numpy()
        assert np.abs((v_t - v_t[0]) - alpha * (r_omega - r_omega[0])).max() < 1e-9
        rate = np.abs(np.diff(v_t + r_omega) / np.diff(table["t"].to_numpy()))
        limit = (1.0 + alpha) / (alpha * m) * mu * kn * overlap
        assert rate.max() <= limit * (1.0 + 1e-3) and rate.max() >= limit * 0.99, (rate.max(), limit)
    return check


def frozen_series(v_t: float):
    """The CSV holds LAMMPS beside Eq. 10; at t = 0 both are the given state."""
    def check(stdout, folder):
        table = pd.read_csv(folder / "f" / "frozen.csv")
        assert table["v_t"].iloc[0] == v_t and table["v_t_theory"].iloc[0] == v_t
        assert (table["v_t"] - table["v_t_theory"]).abs().max() < 1e-5  # the frozen contact's default accuracy
    return check
