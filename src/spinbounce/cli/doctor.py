"""spinbounce doctor: which tangential spring the installed LAMMPS gives, form by form."""

from __future__ import annotations

from .options import json_flag, make_with_runs, out_folder, print_json

HELP = ("run a few tiny collisions and say whether this LAMMPS build's classic granular forms give "
        "the paper's tangential spring or the contact-radius variant (exit 0 once diagnosed; with --strict, "
        "0: paper, 3: variant, 4: neither)")


def register(sub) -> None:
    p = sub.add_parser("doctor", help=HELP, description=HELP + ".")
    p.add_argument("--runs", type=out_folder, default=None, metavar="DIR",
                   help="keep the decks and logs here (default: a temporary folder, removed afterwards)")
    p.add_argument("--strict", action="store_true",
                   help="exit with the verdict's status: 0 every form the paper's, 3 the contact-radius build, "
                        "4 neither")
    json_flag(p)
    p.set_defaults(handler=run)


def _label(c) -> str:
    """What a form's answer means: the spring it gives, and how far its Omega is from that spring's."""
    target = {"paper": c.paper, "contact-radius": c.contact_radius}.get(c.answer)
    if target is None:
        return {"nan": "no answer (LAMMPS gave NaN)", "other": "neither spring"}.get(c.answer, c.answer)
    name = "the paper's spring" if c.answer == "paper" else "the contact-radius spring"
    off = abs(c.measured / target - 1.0)
    return name + (f" (nearest; {off:.1%} from its Omega)" if off >= 1e-3 else "")


def run(args) -> int:
    from ..records import json_ready, software
    from ..studies import doctor

    checks = make_with_runs(lambda _, runs: doctor.diagnose(runs), None, args.runs, "spinbounce-doctor-")
    summary, verdict_status = doctor.verdict({c.form.key: c.answer for c in checks})
    status = verdict_status if args.strict else 0  # a diagnosis made is a success; --strict tells the verdict
    if args.json:
        rows = [{"form": c.form.key, "command": c.form.command, "omega_measured": c.measured,
                 "omega_paper": c.paper, "omega_contact_radius": c.contact_radius, "answer": c.answer,
                 "meaning": _label(c)} for c in checks]
        print_json(json_ready({"checks": rows, "verdict": summary, "verdict_status": verdict_status,
                               "exit_status": status, "upstream": doctor.UPSTREAM, "software": software()}))
        return status
    print(f"LAMMPS {software()['lammps_version']}: Omega = u'(out)/u'(in) - 1 of one collision per form, beside "
          "the paper's spring's and the contact-radius spring's")
    print(f"{'form':40s} {'measured':>10s} {'paper':>10s} {'contact-r':>10s}  gives")
    for c in checks:
        print(f"{c.form.title:40s} {c.measured:10.6f} {c.paper:10.6f} {c.contact_radius:10.6f}  {_label(c)}")
    strict = "" if args.strict else ", --strict exits with the verdict"
    print(f"verdict: {summary} (verdict status {verdict_status}; exit {status}{strict})")
    print(f"upstream: {doctor.UPSTREAM}")
    return status
