"""spinbounce pair: two free spheres collide in LAMMPS, beside the exact reference and the planar theory.

Also the pair scene of ``theory`` and ``collide`` (``--scene pair``): :func:`pair_theory` and
:func:`pair_collide` print the same table.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from ..model.parameters import SceneError, by_name
from .options import (check_run_folder, default_run_dir, force_flag, json_flag, number, optional_number,
                      positive_count)

HELP = "collide two free spheres (pair granular) and compare with the exact reference and the planar theory"
#: Each sphere's options: (flag stem, declared parameter whose range it takes).
SPHERE_OPTIONS = (("m", "m"), ("r", "r"), ("alpha", "alpha"))
VECTORS = (("normal", (0.0, 0.0, 1.0)), ("v-a", (1.0, 0.0, -1.0)), ("v-b", (0.0, 0.0, 0.0)),
           ("w-a", (0.0, 0.0, 0.0)), ("w-b", (0.0, 0.0, 0.0)))
LAW = ("kn", "kt", "gamma_n", "gamma_t", "mu")
#: The most impacts --cost measures over: the cost per collision is steady to a few percent
#: from a few hundred, and each impact is a Python object before LAMMPS starts.
MAX_COST_IMPACTS = 100_000


def cost_count(text: str) -> int:
    """argparse type of --cost: a whole number of impacts in [1, MAX_COST_IMPACTS]."""
    value = positive_count(text)
    if value > MAX_COST_IMPACTS:
        raise argparse.ArgumentTypeError(f"{text!r}: must be at most {MAX_COST_IMPACTS} (the cost per "
                                         "collision is steady to a few percent from a few hundred impacts)")
    return value


def register(sub) -> None:
    p = sub.add_parser("pair", help=HELP, description=(
        f"{HELP}. The state is given at first touch: b's centre at the origin, a's at (r_a + r_b) NORMAL; "
        "vectors are LAMMPS's x y z, spins LAMMPS's angular velocities. A Coulomb cap (--mu) needs motion in one "
        "plane and no gamma_t. Errors are in units of "
        "the larger of |v_a - v_b| and the initial slip speed. --figure and --cost run the studies instead. "
        "(The wall's scene with a sphere b at rest: `spinbounce collide --scene pair`.)"))
    for side in "ab":
        for stem, name in SPHERE_OPTIONS:
            declared = by_name(name)
            p.add_argument(f"--{stem}-{side}", type=number, default=declared.default,
                           help=f"{declared.meaning.split(':')[0]} of {side}; {declared.range_text()} "
                                "(default %(default)s)")
    for name, default in VECTORS:
        p.add_argument(f"--{name}", type=number, nargs=3, default=default, metavar=("X", "Y", "Z"),
                       help=f"(default {' '.join(f'{x:g}' for x in default)})")
    for name in LAW:
        declared = by_name(name)
        p.add_argument(declared.flag, dest=name, type=optional_number if declared.optional else number,
                       default=declared.default,
                       help=f"{declared.meaning}; {declared.range_text()} (default %(default)s)")
    p.add_argument("--dt", type=number, default=None, help="timestep (default: scenes.pair.scene.PAIR_STEPS_PER_HALF_PERIOD)")
    p.add_argument("--out", type=Path, default=None, metavar="DIR", help="run folder (default: spinbounce-runs/pair-*)")
    force_flag(p)
    p.add_argument("--figure", type=Path, default=None, metavar="DIR",
                   help="write pair_validity.png/.pdf/.json into DIR instead")
    p.add_argument("--published", type=Path, default=None, metavar="DIR",
                   help="run the published sphere-sphere benchmarks (Chung & Ooi tests 1, 7, 8; "
                        "studies/validation/pair_cases.py) and write pair_benchmarks.json into DIR instead")
    p.add_argument("--cost", type=cost_count, default=None, metavar="N",
                   help=f"measure LAMMPS's cost per pair collision against the wall's, over N impacts "
                        f"(1 to {MAX_COST_IMPACTS}), instead")
    json_flag(p)
    p.set_defaults(handler=run)


def _print_table(row, lammps: bool) -> None:
    """Both spheres' final velocities and spins: LAMMPS (if run), the exact reference, the planar theory."""
    from ..scenes.pair import QUANTITIES

    print(f"{'':8}" + (f"{'LAMMPS':>14}" if lammps else "") + f"{'exact':>14}{'planar':>14}")
    for name in QUANTITIES:
        print(f"{name:8}" + (f"{row[name]:>14.8f}" if lammps else "")
              + f"{row[name + '_exact']:>14.8f}{row[name + '_planar']:>14.8f}")


def _json_row(row) -> str:
    return json.dumps({k: (v.item() if hasattr(v, "item") else v) for k, v in row.items()}, indent=2)


def _report(batch, row, out: Path | None, as_json: bool) -> int:
    if as_json:
        print(_json_row(row))
        return 0
    lammps = out is not None
    print(f"contact {row.contact_time:.6g} (planar tau {row.tau:.6g}); line of centres turned {row.turn:.4g} rad "
          f"(eps = {row.eps:.4g}, centrifugal ratio {row.centrifugal:.4g})"
          + (f"; dt = {batch.dt:.6g}, {batch.nsteps} steps" if lammps else ""))
    _print_table(row, lammps)
    print((f"LAMMPS vs exact: {row.error:.2e}; " if lammps else "")
          + f"planar theory vs exact (model error): {row.planar_error:.2e}")
    if lammps:
        print(f"run: {out}")
    return 0


def _one_pair(args) -> int:
    from ..scenes.pair import Pair, PairBatch, PairContact, Sphere
    from ..pipeline import run_scene

    check_run_folder(args.out, args.force)
    spheres = {side: Sphere(*(by_name(name).check(getattr(args, f"{stem}_{side}"), f"--{stem}-{side}")
                              for stem, name in SPHERE_OPTIONS)) for side in "ab"}
    pair = Pair(a=spheres["a"], b=spheres["b"], normal=args.normal, v_a=args.v_a, v_b=args.v_b, w_a=args.w_a, w_b=args.w_b)
    batch = PairBatch([pair], PairContact(*(getattr(args, name) for name in LAW)), args.dt)
    out = args.out or default_run_dir("pair", vars(args) | {"handler": None})
    result = run_scene(batch, out)
    return _report(result.scene, result.table.iloc[0], out, args.json)


def _scene_pair(model, b, state: dict, dt=None):
    """The wall scene's state as a pair batch: sphere a (the model's) against b at rest."""
    from ..scenes.pair.kind import pair_contact, pairs_from_states
    from ..scenes.pair.scene import PairBatch

    row = [state.get(k, 0.0) for k in ("v_n", "v_t", "omega", "v_s", "omega_s", "omega_n")]
    return PairBatch(pairs_from_states(model, b, [row]), pair_contact(model), dt)


def pair_theory(args, model, b, state: dict | None) -> int:
    """``theory --scene pair``: the planar matrix of a's state (b at rest), or one state's references."""
    from ..scenes.pair.kind import CAPPED_NO_MATRIX, pair_contact, planar_Omega, planar_matrix
    from ..scenes.pair.table import pair_table
    from ..exact import pair as planar

    if state is not None:
        batch = _scene_pair(model, b, state)
        return _report(batch, pair_table(batch, None).iloc[0], None, args.json)
    if model.mu is not None:
        raise SceneError("mu", model.mu, f"{CAPPED_NO_MATRIX} (give a state: --vn, --vt, --omega)")
    law = pair_contact(model).law()
    report = {"theory_kind": "pair planar", "matrix": planar_matrix(model, b).tolist(),
              "order": ["v_n", "v_t", "r_omega"], "Omega": planar_Omega(model, b),
              "alpha_equivalent": planar.equivalent_alpha(model.m, model.alpha, b.m, b.alpha),
              "tau": float(planar.contact_time(model.m, b.m, law["kn"], law["gamma_n"])),
              "model_error": "the planar theory holds the line of centres fixed: it is exact only as "
                             "eps = v_t tau/(r + r_b) -> 0 (figures/pair_validity); give a state for the exact reference"}
    if args.json:
        print(json.dumps(report, indent=2))
        return 0
    print(f"theory: planar pair (sphere b: m_b = {b.m:g}, r_b = {b.r:g}, alpha_b = {b.alpha:g}, at rest)")
    print(f"tau   = {report['tau']:.10g}   (pi sqrt(m*/kn), m* the reduced mass)")
    print(f"Omega = {report['Omega']:.10g}   (the wall's at alpha_eq = {report['alpha_equivalent']:.10g})")
    print("scattering matrix of sphere a, (v_n, v_t, r*omega) before -> after:")
    for matrix_row in report["matrix"]:
        print("   ", "  ".join(f"{x:11.8f}" for x in matrix_row))
    print(f"model error: {report['model_error']}")
    return 0


def pair_collide(args, model, b, state: dict) -> int:
    """``collide --scene pair``: sphere a against b at rest in LAMMPS, beside both references."""
    from ..pipeline import run_scene

    if args.tolerance is not None:
        raise SceneError("--tolerance", args.tolerance, "is for the wall only: a pair runs at --dt or its default "
                                                       "step, and reports its error against the exact reference")
    batch = _scene_pair(model, b, state, args.dt)
    out = args.out or default_run_dir("collide-pair", {"model": repr(model), "b": repr(b), **state, "dt": batch.dt})
    result = run_scene(batch, out)
    return _report(result.scene, result.table.iloc[0], out, args.json)


def _published(out: Path, as_json: bool) -> int:
    import tempfile

    from ..records import software, to_json, write_atomic
    from ..studies.validation.pair_cases import PAIR_BENCHMARKS, run_pair_benchmark

    with tempfile.TemporaryDirectory() as scratch:
        records = [run_pair_benchmark(bench, Path(scratch)) for bench in PAIR_BENCHMARKS.values()]
    Path(out).mkdir(parents=True, exist_ok=True)
    path = write_atomic(Path(out) / "pair_benchmarks.json", to_json({"benchmarks": records, **software()}))
    if as_json:
        print(json.dumps(records, indent=2))
        return 0
    for r in records:
        print(f"{r['name']:<22} {'agrees' if r['agrees'] else 'DISAGREES'}: {r['published']}; {r['quantity']} "
              f"within {r['lammps_vs_published']:.1e} (bound {r['tolerance']:.1e}); LAMMPS vs exact "
              f"{r['lammps_vs_exact']:.1e}, planar vs exact {r['planar_vs_exact']:.1e}")
    print(f"wrote {path}")
    return 0 if all(r["agrees"] for r in records) else 1


def run(args) -> int:
    if args.published is not None:
        return _published(args.published, args.json)
    if args.figure is not None:
        from ..figures.pairs import make_pair_validity

        record = make_pair_validity(args.figure)
        print(f"wrote {record.png}, {record.pdf}, {record.json}")
        return 0
    if args.cost is not None:
        from ..studies.pairs import cost_lines, pair_to_wall_cost

        report = pair_to_wall_cost(args.cost)
        print(json.dumps(report, indent=2) if args.json else "\n".join(cost_lines(report)))
        return 0
    return _one_pair(args)
