"""Unusual and wrong invocations of the spinbounce command, each with what it must do.

Three kinds (tests/test_fuzz.py runs them):

- ``refused``: exit status 2 and one line on stderr that names the option or parameter and the
  value given (``needles``), no traceback, and every file in the folder left as it was;
- ``ok``: exit status 0 and a result checked against the physics (``check(stdout, folder)``),
  never against the command's own numbers;
- ``pipe``: the output's reader goes away after one line; the command ends quietly.

Every case finishes in seconds: refusals come before LAMMPS starts, and runs are one tiny
collision. The checks and the files the cases meet are in tests/fuzz_support.py.
"""

from __future__ import annotations

import shlex
from dataclasses import dataclass
from typing import Callable

from fuzz_support import (LAMMPS_TOLERANCE, THEORY_TOLERANCE, calibrated, capped_frozen, chunks_listed, contact_time,
                          figure_beside_user_file, frozen_series, gross_slip, initial_is, omega_is, paper_bounce,
                          pair_meets_its_reference, printed, reversed_normal, unchanged_tangential)

@dataclass(frozen=True)
class Case:
    id: str
    argv: tuple[str, ...]
    expect: str
    needles: tuple[str, ...] = ()
    files: tuple[str, ...] = ()
    check: Callable | None = None
    #: The module run by ``python -m``: the command's own, or the package's (python -m spinbounce).
    module: str = "spinbounce.cli"


def refused(id_: str, line: str, *needles: str, files: tuple[str, ...] = (), module: str = "spinbounce.cli") -> Case:
    return Case(id_, tuple(shlex.split(line)), "refused", needles, files, module=module)


def ok(id_: str, line: str, check: Callable, files: tuple[str, ...] = (), module: str = "spinbounce.cli") -> Case:
    return Case(id_, tuple(shlex.split(line)), "ok", (), files, check, module)


def pipe(id_: str, line: str) -> Case:
    return Case(id_, tuple(shlex.split(line)), "pipe")

STATE = "--vn -1 --vt 0 --omega 0"
FROZEN = "frozen --z 0.45 --vt 1 --omega 0 --t-end 1 --out f"
CALIBRATE = "calibrate --e 0.9 --contact-time 1 --beta 0.5 --no-run"

NUMBERS = [
    ok("e-notation-negative", "theory --json --vn -1e-3 --vt 0 --omega 0", reversed_normal(-1e-3)),
    ok("e-notation-upper", "theory --json --vn -1E-3 --vt 0 --omega 0", reversed_normal(-1e-3)),
    ok("e-notation-equals", "theory --json --vn=-1e-3 --vt=0 --omega=0", reversed_normal(-1e-3)),
    ok("e-notation-plus-exponent", "theory --json --vn -1e+0 --vt 0 --omega 0", reversed_normal(-1.0)),
    ok("leading-dot", "theory --json --vn -.5 --vt 0 --omega 0", reversed_normal(-0.5)),
    ok("trailing-dot", "theory --json --vn -2. --vt 0 --omega 0", reversed_normal(-2.0)),
    ok("tiny-vn", "theory --json --vn -1e-300 --vt 0 --omega 0", reversed_normal(-1e-300)),
    ok("huge-vn", "theory --json --vn -1e300 --vt 0 --omega 0", reversed_normal(-1e300)),
    ok("spaces-around", "theory --json --vn ' -1 ' --vt 0 --omega 0", reversed_normal(-1.0)),
    ok("arabic-indic-digit", "theory --json --vn -1 --vt ١ --omega 0", initial_is(v_t=1.0)),
    ok("fullwidth-digit", "theory --json --vn -1 --vt ２ --omega 0", initial_is(v_t=2.0)),
    ok("underscore-digits", "theory --json --vn -1 --vt 1_000 --omega 0", initial_is(v_t=1000.0)),
    refused("nan", "theory --vn nan --vt 0 --omega 0", "--vn", "nan"),
    refused("nan-upper", "theory --vn -1 --vt NaN --omega 0", "--vt", "NaN"),
    refused("inf", "theory --vn -1 --vt inf --omega 0", "--vt", "inf"),
    refused("minus-inf", "theory --vn -inf --vt 0 --omega 0", "--vn", "-inf"),
    refused("infinity-word", "theory --vn -1 --vt Infinity --omega 0", "--vt", "Infinity"),
    refused("overflow-1e400", "theory --vn -1 --vt 1e400 --omega 0", "--vt", "1e400"),
    refused("overflow-negative", "theory --vn -1e400 --vt 0 --omega 0", "--vn", "-1e400"),
    refused("underflow-kn", "theory --kn 1e-400", "kn", "0.0"),
    refused("hex", "theory --vn -1 --vt 0x10 --omega 0", "--vt", "0x10"),
    refused("empty", "theory --vn -1 --vt '' --omega 0", "--vt", "''"),
    refused("word", "theory --vn -1 --vt one --omega 0", "--vt", "one"),
    refused("comma-decimal", "theory --vn -1 --vt 0,5 --omega 0", "--vt", "0,5"),
    refused("two-dots", "theory --vn -1 --vt 1.2.3 --omega 0", "--vt", "1.2.3"),
    refused("unit-suffix", "theory --vn -1m/s --vt 0 --omega 0", "--vn", "-1m/s"),
    refused("fraction", "theory --alpha 2/5", "--alpha", "2/5"),
    refused("vn-missing-value", "theory --vn", "--vn"),
    refused("vn-zero", "theory --vn 0 --vt 0 --omega 0", "v_n", "0.0"),
    refused("vn-minus-zero", "theory --vn -0 --vt 0 --omega 0", "v_n", "-0.0"),
    refused("vn-positive", "theory --vn 1 --vt 0 --omega 0", "v_n", "1.0"),
]

MODEL_LIMITS = [
    refused("kn-zero", "theory --kn 0", "kn", "0.0"),
    refused("kn-negative", "theory --kn -10", "kn", "-10.0"),
    refused("kt-negative", "theory --kt -1", "kt", "-1.0"),
    ok("kt-zero", f"theory --json --kt 0 {STATE.replace('--vt 0', '--vt 0.7').replace('--omega 0', '--omega 0.4')}",
       unchanged_tangential(-1.0, 0.7, 0.2)),
    ok("kt-zero-omega", "theory --json --kt 0", omega_is(0.0, THEORY_TOLERANCE)),
    ok("paper-defaults-omega", "theory --json", omega_is(-1.28384, 1e-5)),
    ok("magic-ratio", "theory --json --alpha 0.4 --kn 7 --kt 2", omega_is(-2.0)),
    ok("magic-ratio-e", "theory --json --alpha 4e-1 --kn 7e0 --kt 2e0", omega_is(-2.0)),
    ok("contact-time-m", f"theory --json --mass 4 --kn 1 {STATE}", contact_time(4.0, 1.0)),
    ok("contact-time-alias", f"theory --json --m 2.5e-1 --kn 1e2 {STATE}", contact_time(0.25, 100.0)),
    refused("alpha-zero", "theory --alpha 0", "alpha", "0.0"),
    refused("alpha-above-one", "theory --alpha 1.0001", "alpha", "1.0001"),
    refused("alpha-negative", "theory --alpha -0.4", "alpha", "-0.4"),
    ok("alpha-one", "theory --json --alpha 1 --kn 2 --kt 1", omega_is(-2.0)),
    refused("mass-zero", "theory --mass 0", "m", "0.0"),
    refused("mass-negative", "theory --m -1", "m", "-1.0"),
    refused("radius-zero", "theory --radius 0", "r", "0.0"),
    refused("radius-negative", "theory --r -0.5", "r", "-0.5"),
    refused("gamma-n-negative", "theory --gamma-n -0.1", "gamma_n", "-0.1"),
    refused("gamma-n-critical", "theory --gamma-n 6.33", "gamma_n", "6.33"),
    refused("gamma-n-far-overdamped", "theory --gamma-n 1e6", "gamma_n", "1000000.0"),
    refused("gamma-t-negative", "theory --gamma-t -1", "gamma_t", "-1.0"),
    refused("mu-negative", "theory --mu -0.1", "mu", "-0.1"),
    refused("mu-nan", "theory --mu nan", "--mu", "nan"),
    refused("mu-word", "theory --mu lots", "--mu", "lots"),
    ok("mu-none", f"theory --json --mu none {STATE}", reversed_normal(-1.0)),
    ok("mu-none-upper", f"theory --json --mu NONE {STATE}", reversed_normal(-1.0)),
    ok("mu-zero", "theory --json --mu 0 --vn -1 --vt 0.5 --omega 1", unchanged_tangential(-1.0, 0.5, 0.5)),
    ok("mu-gross-slip", "theory --json --mu 0.1 --vn -1 --vt 1 --omega 0", gross_slip(-1.0, 1.0, 0.1)),
    ok("mu-gross-slip-e", "theory --json --mu 5e-2 --vn -2e0 --vt 3 --omega 0", gross_slip(-2.0, 3.0, 0.05)),
    refused("normal-unknown", "theory --normal cubic", "--normal", "cubic"),
    refused("normal-upper", "theory --normal HOOKE", "--normal", "HOOKE"),
    refused("wall-unknown", "theory --wall steel", "--wall", "steel"),
    refused("limit-damping-value", "theory --limit-damping yes", "yes"),
    refused("classic-hertz", "collide --wall classic --normal hertz --out c", "hertz", "classic"),
    refused("hertz-tunnels", "collide --normal hertz --vn -50 --vt 0 --omega 0 --out c", "v_n", "-50.0"),
    refused("vn-tunnels", "collide --vn -1.6 --vt 0 --omega 0 --out c", "v_n = -1.6"),
]

FLAGS = [
    refused("no-command", "", "COMMAND"),
    refused("unknown-command", "colide", "colide"),
    refused("unknown-flag", "theory --foo 1", "--foo"),
    refused("unknown-flag-collide", "collide --t-end 5 --out c", "--t-end"),
    refused("single-dash", "theory -vn -1", "-vn"),
    refused("twice", "theory --vn -1 --vn -2 --vt 0 --omega 0", "--vn", "twice"),
    refused("twice-alias", "collide --vn -1 --v-n -2 --out c", "--v-n", "twice"),
    refused("twice-mass", "theory --mass 1 --m 2", "--m", "twice"),
    refused("twice-out", "figures --out a --out b", "--out", "twice"),
    refused("omega-and-romega", "theory --vn -1 --vt 0 --omega 1 --romega 0.5", "omega"),
    refused("dt-and-tolerance", "collide --dt 0.01 --tolerance 1e-4 --out c", "--tolerance", "--dt"),
    refused("beta-and-omega", f"{CALIBRATE} --Omega -1", "--Omega", "--beta"),
    refused("gamma-t-and-ratio", f"{CALIBRATE} --gamma-t 0 --kt-over-kn 0.2", "--kt-over-kn", "--gamma-t"),
    refused("check-and-regenerate", "references --check --regenerate", "--regenerate", "--check"),
    refused("references-no-mode", "references", "--check", "--regenerate"),
    refused("references-unknown-case", "references --check --case nope", "--case", "nope"),
    ok("frozen-mu", f"{FROZEN} --mu 0.3", capped_frozen(0.3, 0.05)),
    refused("frozen-mu-classic", f"{FROZEN} --mu 0.3 --wall classic", "mu", "0.3", "classic"),
    refused("frozen-missing-z", "frozen --vt 1 --omega 0 --t-end 1 --out f", "--z"),
    refused("calibrate-missing-e", "calibrate --contact-time 1 --beta 0.5 --no-run", "--e"),
    refused("figures-unknown", "figures --only fig9", "--only", "fig9"),
    refused("figures-empty-only", "figures --only ,", "--only", "','"),
    refused("benchmarks-unknown", "benchmarks --only nope", "--only", "nope"),
    refused("sweep-scene-and-flag", "sweep ok.toml --out s --alpha 0.3", "--alpha", files=("ok.toml",)),
    refused("sweep-speed-and-vn", "sweep --n 10 --speed 0.5 1 --vn -1 -0.5 --out s --list-chunks", "--speed", "--vn"),
    refused("sweep-vn-one-value", "sweep --n 10 --vn -1 --out s --list-chunks", "--vn"),
    refused("sweep-no-out", "sweep --n 10", "--out"),
    refused("pair-two-components", "pair --v-a 1 2", "--v-a"),
    refused("pair-zero-normal", "pair --normal 0 0 0", "normal"),
    refused("pair-kn-negative", "pair --kn -1", "kn", "-1.0"),
    ok("pair-mu-3d", "pair --mu 0.3 --omega-s 1", pair_meets_its_reference("r*omega_s")),
    ok("pair-mu-gamma-t", "pair --mu 0.3 --gamma-t 0.5", pair_meets_its_reference("r*omega")),
    refused("limit-damping-as-value", "theory --limit-damping=true", "--limit-damping"),
]

COUNTS = [
    ok("n-e-notation", "sweep --n 1e3 --out s --list-chunks --json", chunks_listed(1000)),
    ok("n-integral-float", "sweep --n 25.0 --out s --list-chunks --json", chunks_listed(25)),
    ok("n-chunk-size-e", "sweep --n 1e2 --chunk-size 1e1 --out s --list-chunks --json", chunks_listed(100)),
    refused("n-fraction", "sweep --n 10.5 --out s", "--n", "10.5"),
    refused("n-zero", "sweep --n 0 --out s", "n", "0"),
    refused("n-negative", "sweep --n -5 --out s", "n", "-5"),
    refused("n-word", "sweep --n ten --out s", "--n", "ten"),
    refused("n-overflow", "sweep --n 1e400 --out s", "--n", "1e400"),
    refused("chunk-size-zero", "sweep --n 10 --chunk-size 0 --out s", "chunk_size", "0"),
    refused("workers-zero", "sweep --n 10 --workers 0 --out s", "--workers", "0"),
    refused("workers-negative", "sweep --n 10 --workers -1 --out s", "--workers", "-1"),
    refused("workers-fraction", "sweep --n 10 --workers 1.5 --out s", "--workers", "1.5"),
    refused("workers-word", "sweep --n 10 --workers all --out s", "--workers", "all"),
    refused("bench-workers-zero", "bench --workers 0", "--workers", "0"),
    refused("reproduce-workers-zero", "reproduce --workers 0", "--workers", "0"),
    refused("reproduce-workers-beyond-the-cores", "reproduce --only pair_validity --workers 4096", "--workers", "4096",
            "core"),
    refused("bench-workers-negative", "bench --workers -1", "--workers", "-1"),
    refused("bench-workers-above-cores", "bench --workers 4096", "--workers", "4096"),
    refused("bench-n-lmp-zero", "bench --n-lmp 0", "--n-lmp", "0"),
    refused("bench-n-lmp-fraction", "bench --n-lmp 2.5", "--n-lmp", "2.5"),
    refused("bench-n-batched-small", "bench --n-batched 1 --n-lmp 5", "--n-batched", "1"),
    refused("bench-n-models-negative", "bench --n-models -1e5", "--n-models", "-1e5"),
    refused("bench-chunk-size-word", "bench --chunk-size many", "--chunk-size", "many"),
    refused("bench-seed-fraction", "bench --seed 0.5", "--seed", "0.5"),
    refused("hertz-points-zero", "hertz --points 0", "--points", "0"),
    refused("hertz-points-one", "hertz --points 1", "points", "1"),
    refused("hertz-points-nan", "hertz --points nan", "--points", "nan"),
    refused("hertz-v-min-negative", "hertz --v-min -1", "v_min", "-1"),
    refused("hertz-v-max-below-min", "hertz --v-min 1 --v-max 0.5", "v_max", "0.5"),
    refused("hertz-kn-inf", "hertz --kn inf", "--kn", "inf"),
    refused("hertz-tunnelling-grid", "hertz --kn 10", "v_n = -1.5"),
    refused("frozen-every-zero", f"{FROZEN} --every 0", "every", "0"),
    refused("frozen-every-fraction", f"{FROZEN} --every 1.5", "--every", "1.5"),
]

TIME = [
    refused("dt-too-large", f"collide {STATE} --dt 0.7 --out c", "dt", "0.7"),
    refused("dt-zero", f"collide {STATE} --dt 0 --out c", "dt", "0.0"),
    refused("dt-negative", f"collide {STATE} --dt -0.01 --out c", "dt", "-0.01"),
    refused("dt-too-small", f"collide {STATE} --dt 1e-9 --out c", "dt", "1e-09"),
    refused("tolerance-zero", f"collide {STATE} --tolerance 0 --out c", "tolerance", "0"),
    refused("tolerance-negative", f"collide {STATE} --tolerance -1e-4 --out c", "tolerance", "-0.0001"),
    refused("tolerance-above-one", f"collide {STATE} --tolerance 2 --out c", "tolerance", "2"),
    refused("tolerance-unreachable", f"collide {STATE} --tolerance 1e-300 --out c", "tolerance", "1e-300"),
    refused("frozen-t-end-huge", "frozen --z 0.1 --vt 1 --omega 0 --t-end 1e9 --out f", "t_end", "1000000000.0"),
    refused("frozen-t-end-zero", "frozen --z 0.1 --vt 1 --omega 0 --t-end 0 --out f", "t_end", "0.0"),
    refused("frozen-t-end-negative", "frozen --z 0.1 --vt 1 --omega 0 --t-end -1 --out f", "t_end", "-1.0"),
    refused("frozen-dt-too-small", f"{FROZEN} --dt 1e-12", "dt", "1e-12"),
    refused("frozen-z-zero", "frozen --z 0 --vt 1 --omega 0 --t-end 1 --out f", "z", "0.0"),
    refused("frozen-z-radius", "frozen --z 0.5 --vt 1 --omega 0 --t-end 1 --out f", "z", "0.5"),
    refused("frozen-z-above", "frozen --z 2 --vt 1 --omega 0 --t-end 1 --out f", "z", "2.0"),
    refused("sweep-dt-too-large", "sweep --n 10 --dt 1 --out s", "dt", "1"),
    refused("sweep-dt-too-small", "sweep --n 10 --dt 1e-12 --out s", "dt", "1e-12"),
    refused("calibrate-e-zero", f"{CALIBRATE.replace('--e 0.9', '--e 0')}", "e", "0"),
    refused("calibrate-e-above-one", f"{CALIBRATE.replace('--e 0.9', '--e 1.5')}", "e", "1.5"),
    refused("calibrate-beta-above-one", f"{CALIBRATE.replace('--beta 0.5', '--beta 2')}", "beta", "2"),
    refused("calibrate-omega-positive", f"{CALIBRATE.replace('--beta 0.5', '--Omega 1')}", "beta", "-2"),
    refused("calibrate-contact-time-zero", f"{CALIBRATE.replace('--contact-time 1', '--contact-time 0')}",
            "contact_time", "0"),
    refused("calibrate-contact-time-nan", f"{CALIBRATE.replace('--contact-time 1', '--contact-time nan')}",
            "--contact-time", "nan"),
    ok("calibrate-no-run", f"{CALIBRATE} --json", calibrated(0.9, 1.0)),
    ok("calibrate-e-notation", "calibrate --e 9e-1 --contact-time 2e0 --beta 5e-1 --no-run --json", calibrated(0.9, 2.0)),
]

STUDIES = ("figures", "claims", "hertz", "benchmarks", "two-walls", "restitution", "accuracy")

FILES = [
    *(refused(f"{study}-out-is-a-file", f"{study} --out notes.txt", "--out", "notes.txt", files=("notes.txt",))
      for study in STUDIES),
    *(refused(f"{study}-out-unwritable", f"{study} --out /proc/spinbounce-out", "--out", "/proc/spinbounce-out")
      for study in STUDIES),
    *(refused(f"{study}-out-under-a-file", f"{study} --out notes.txt/figs", "--out", "notes.txt/figs",
              files=("notes.txt",)) for study in ("figures", "accuracy", "two-walls")),
    refused("figures-runs-is-a-file", "figures --only fig2 --runs notes.txt", "--runs", "notes.txt",
            files=("notes.txt",)),
    refused("two-walls-runs-is-a-file", "two-walls --runs notes.txt", "--runs", "notes.txt", files=("notes.txt",)),
    refused("claims-runs-is-a-file", "claims --runs notes.txt", "--runs", "notes.txt", files=("notes.txt",)),
    refused("calibrate-runs-is-a-file", f"{CALIBRATE} --runs notes.txt", "--runs", "notes.txt", files=("notes.txt",)),
    refused("doctor-runs-is-a-file", "doctor --runs notes.txt", "--runs", "notes.txt", files=("notes.txt",)),
    refused("bench-out-is-a-folder", "bench --out folder", "--out", "folder", files=("folder",)),
    refused("bench-out-unwritable", "bench --out /proc/bench.json", "--out", "/proc/bench.json"),
    refused("bench-keep-runs-is-a-file", "bench --keep-runs notes.txt", "--keep-runs", "notes.txt",
            files=("notes.txt",)),
    refused("frozen-out-earlier-run", FROZEN.replace("--out f", "--out run"), "--out", "run", "--force",
            files=("run",)),
    refused("frozen-out-is-a-file", FROZEN.replace("--out f", "--out series.csv"), "--out", "series.csv",
            files=("series.csv",)),
    refused("frozen-out-unwritable", FROZEN.replace("--out f", "--out /proc/f"), "--out", "/proc/f"),
    refused("frozen-out-under-a-file", FROZEN.replace("--out f", "--out notes.txt/f"), "--out", "notes.txt/f",
            files=("notes.txt",)),
    refused("collide-earlier-run", f"collide {STATE} --out run", "--out", "run", files=("run",)),
    refused("fit-missing", "fit nothere", "nothere"),
    refused("fit-empty-folder", "fit emptydir", "emptydir", files=("emptydir",)),
    refused("sweep-scene-missing", "sweep nothere.toml --out s", "nothere.toml"),
    refused("sweep-scene-folder", "sweep folder --out s", "folder", files=("folder",)),
    refused("sweep-scene-not-toml", "sweep bad.toml --out s", "bad.toml", files=("bad.toml",)),
    refused("sweep-scene-empty", "sweep empty.toml --out s", "states", files=("empty.toml",)),
    refused("sweep-scene-unknown-key", "sweep unknown.toml --out s", "colour", files=("unknown.toml",)),
    refused("sweep-scene-typo-key", "sweep typo.toml --out s", "kn_typo", files=("typo.toml",)),
    refused("sweep-scene-word-value", "sweep words.toml --out s", "mu", "high", files=("words.toml",)),
    refused("sweep-scene-negative-mu", "sweep negative.toml --out s", "mu", "-0.3", files=("negative.toml",)),
    refused("sweep-scene-alpha", "sweep alpha.toml --out s", "alpha", "2.0", files=("alpha.toml",)),
    refused("sweep-scene-n-text", "sweep n_text.toml --out s", "n", "ten", files=("n_text.toml",)),
    refused("sweep-scene-vn-scalar", "sweep vn_one.toml --out s", "v_n", files=("vn_one.toml",)),
    ok("sweep-scene-listed", "sweep ok.toml --out s --list-chunks --json", chunks_listed(10), files=("ok.toml",)),
    refused("sweep-out-is-a-file", "sweep --n 10 --out notes.txt", "notes.txt", files=("notes.txt",)),
    refused("references-check-missing-dir", "references --check --dir nothere", "nothere"),
]

RUNS = [
    ok("collide-e-notation", "collide --json --vn -1e-3 --vt 0 --omega 0 --out c",
       reversed_normal(-1e-3, LAMMPS_TOLERANCE)),
    ok("collide-gross-slip", "collide --json --mu 0.1 --vn -1 --vt 1 --omega 0 --out c",
       gross_slip(-1.0, 1.0, 0.1, tolerance=LAMMPS_TOLERANCE)),
    ok("collide-kt-zero", "collide --json --kt 0 --vn -1 --vt 0.7 --omega 0.4 --out c",
       unchanged_tangential(-1.0, 0.7, 0.2, LAMMPS_TOLERANCE)),
    ok("collide-earlier-run-forced", f"collide --json {STATE} --out run --force", reversed_normal(-1.0, LAMMPS_TOLERANCE),
       files=("run",)),
    ok("frozen-small", FROZEN, frozen_series(1.0)),
    ok("figures-runs-beside-user-file", "figures --only fig2 --runs figout", figure_beside_user_file("fig2"),
       files=("figout",)),
    ok("figures-out-beside-user-file", "figures --only fig2 --out figout", figure_beside_user_file("fig2", "figout"),
       files=("figout",)),
    ok("frozen-e-notation", "frozen --z 4.5e-1 --vt 1e0 --omega 0 --t-end 1e0 --out f", frozen_series(1.0)),
]

PIPES = [
    pipe("pipe-theory", "theory"),
    pipe("pipe-theory-json", "theory --json"),
    pipe("pipe-help", "collide --help"),
    pipe("pipe-top-help", "--help"),
    pipe("pipe-list-chunks", "sweep --n 1e5 --chunk-size 10 --out s --list-chunks"),
]

TOP = [
    ok("version", "--version", printed("spinbounce ")),
    ok("help", "--help", printed("collide", "sweep", "fit")),
    ok("command-help", "theory --help", printed("--kn", "--mu")),
    refused("debug-after-command", "theory --debug", "--debug"),
    refused("dash-dash", "theory -- --vn -1", "--vn"),
]

#: Found failing after the first set passed: each now refused at its root, or checked.
FOUND_LATER = [
    refused("dt-denormal", f"collide {STATE} --dt 5e-324 --out c", "dt", "5e-324", "1e+08"),
    refused("frozen-dt-denormal", f"{FROZEN} --dt 5e-324", "dt", "5e-324", "1e+08"),
    refused("frozen-dt-coarse", f"{FROZEN} --dt 1", "dt = 1.0", "steps per half-period", "at most"),
    refused("collide-dt-coarse", f"collide {STATE} --dt 0.3 --out c", "dt = 0.3", "steps per half-period"),
    refused("fit-corrupt", "fit corrupt", "corrupt/chunks/chunk-0000-000000.parquet", files=("corrupt",)),
    refused("fit-random-bytes", "fit random", "random/chunks/chunk-0000-000000.parquet", files=("random",)),
    refused("fit-corrupt-selected", "fit corrupt --alpha 0.4", "corrupt/chunks", files=("corrupt",)),
    refused("fit-text-file", "fit notes.txt", "notes.txt", "Parquet", files=("notes.txt",)),
    refused("fit-text-named-parquet", "fit x.parquet", "x.parquet", files=("x.parquet",)),
    refused("fit-foreign", "fit foreign", "foreign/chunks", "v_n_initial", files=("foreign",)),
    refused("fit-foreign-plot", "fit foreign --plot x.png", "foreign/chunks", "v_n_initial", files=("foreign",)),
    refused("sweep-too-many-chunks", "sweep --n 1e12 --out s --list-chunks", "n = 1000000000000", "100000"),
    refused("sweep-over-an-hour", "sweep --n 1e9 --out s", "--n = 1000000000", "core-hours", "--force"),
    ok("sweep-over-an-hour-listed", "sweep --n 1e9 --out s --list-chunks --json", chunks_listed(10**9)),
    refused("sweep-scene-vn-positive", "sweep vn_positive.toml --out s", "v_n", "0.1", "< 0",
            files=("vn_positive.toml",)),
    refused("sweep-vn-positive-flags", "sweep --n 10 --vn 0.1 1.5 --out s", "v_n", "0.1", "< 0"),
    refused("sweep-workers-above-cores", "sweep --n 10 --workers 4096 --out s", "--workers", "4096", "core"),
    refused("pair-earlier-run", "pair --out run", "--out", "run", "--force", files=("run",)),
    refused("bench-pairs-huge", "bench --n-pairs 1e12", "--n-pairs", "1e12", "100000"),
    refused("bench-pairs-zero", "bench --n-pairs 0", "--n-pairs", "0", ">= 1"),
    refused("bench-pairs-fraction", "bench --n-pairs 2.5", "--n-pairs", "2.5"),
    refused("pair-b-state-on-the-wall", "collide --v-n-b 1 --out c", "v_n_b", "scene = pair"),
    refused("pair-b-runs-away", "pair --v-n-b -2 --out p", "v_n - v_n_b", "1.0", "< 0"),
    # issue 28: every file a command reads, broken, is one line naming it; nothing of the user's replaced
    refused("sweep-record-truncated", "sweep --n 10 --out swept", "swept/sweep.json", "not valid JSON",
            files=("sweep-truncated",)),
    refused("sweep-record-binary", "sweep --n 10 --out swept", "swept/sweep.json", "not text", files=("sweep-binary",)),
    refused("sweep-record-foreign", "sweep --n 10 --out swept", "swept/sweep.json", "object", files=("sweep-list",)),
    refused("references-corrupt-manifest", "references --check --dir refs --case defaults", "refs/MANIFEST.json",
            "not valid JSON", files=("refs-corrupt-manifest",)),
    refused("references-foreign-manifest", "references --check --dir refs --case defaults", "refs/MANIFEST.json",
            "object", files=("refs-list-manifest",)),
    refused("references-table-words", "references --check --dir refs --case defaults", "refs/defaults.csv",
            "not a number", files=("refs-text-table",)),
    refused("references-table-ragged", "references --check --dir refs --case defaults", "refs/defaults.csv",
            "number of fields", files=("refs-ragged-table",)),
    refused("sweep-into-unrecorded-chunks", "sweep --n 10 --out corrupt", "corrupt", "no sweep record",
            files=("corrupt",)),
    refused("fit-plot-over-a-users-file", "fit corrupt --plot user.png", "--plot", "user.png", "--force",
            files=("corrupt", "user.png")),
    refused("figures-over-a-users-image", "figures --only fig2 --out figout", "figout/fig2.png",
            "not written by spinbounce", "--force", files=("figout-fig2.png",)),
    refused("bench-over-an-earlier-report", "bench --quick", "--out", "bench.json", "--force", files=("bench.json",)),
    refused("collide-mass-unresolved", f"collide {STATE} --mass 1e-300 --out c", "m = 1e-300", "last place"),
    refused("collide-vn-unresolved", "collide --vn -1e-20 --vt 0 --omega 0 --out c", "v_n = -1e-20", "last place"),
    ok("collide-vt-huge", "collide --json --vn -1 --vt 1e6 --omega 0 --out c", paper_bounce(1e6)),
    ok("collide-vt-huge-sliding", "collide --json --mu 0.1 --vn -1 --vt 1e6 --omega 0 --out c",
       gross_slip(-1.0, 1e6, 0.1, tolerance=LAMMPS_TOLERANCE)),
    ok("collide-spin-huge", "collide --json --vn -1 --vt 0 --omega 40000 --out c", paper_bounce(0.0, 20000.0)),
    refused("frozen-mu-kt-zero", f"{FROZEN} --mu 0.3 --kt 0", "kt = 0.0", "cap"),
    refused("sweep-chunk-record-truncated", "sweep --n 10 --out swept --chunk 0", "swept/sweep.json", "not valid JSON",
            files=("sweep-truncated",)),
    refused("sweep-vn-unresolved", "sweep --n 10 --vn -1e-20 -1e-21 --out s", "v_n", "last place"),
    refused("sweep-b-state", "sweep --scene pair --n 3 --v-n-b 1 --out s", "--v-n-b", "b at rest", "collide --scene pair"),
    refused("pair-dt-too-fine", "pair --dt 1e-9 --out p", "dt", "1e-09", "limit"),
    refused("pair-on-the-wall", "pair --scene wall --out p", "--scene", "wall", "collide"),
    refused("collide-out-holds-a-users-deck", "collide --out mydeck", "--out", "mydeck", "in.lammps", "--force",
            files=("mydeck",)),
    refused("reproduce-out-is-a-file", "reproduce --only pair_validity --out notes.txt", "--out", "notes.txt",
            files=("notes.txt",)),
    refused("frozen-every-beyond-the-limit", f"{FROZEN} --every 1e12", "every", "1e+12", "limit"),
    refused("frozen-t-end-beyond-any-step", "frozen --z 0.45 --vt 1 --omega 0 --t-end 1e300 --out f", "t_end", "limit"),
    refused("figures-runs-holds-user-file", "figures --only fig2 --runs figout", "--runs", "figout/fig2",
            files=("figout-fig2",)),
    ok("python-m-spinbounce", "--version", printed("spinbounce "), module="spinbounce"),
    refused("python-m-spinbounce-refusal", "theory --vn nan", "--vn", "nan", module="spinbounce"),
]

CASES = [*NUMBERS, *MODEL_LIMITS, *FLAGS, *COUNTS, *TIME, *FILES, *RUNS, *PIPES, *TOP, *FOUND_LATER]
