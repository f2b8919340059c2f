"""spinbounce doctor: which tangential spring the installed LAMMPS gives, form by form."""

from __future__ import annotations

from .options import json_flag, make_with_runs, out_folder, print_json

HELP = ("run a few tiny collisions and say whether this LAMMPS build's classic granular forms give "
        "the paper's tangential spring or the contact-radius variant (exit 0: paper, 3: variant, 4: neither)")


def register(sub) -> None:
    p = sub.add_parser("doctor", help=HELP, description=HELP + ".")
    p.add_argument("--run-dir", type=out_folder, default=None, metavar="DIR",
                   help="keep the decks and logs here (default: a temporary folder, removed afterwards)")
    json_flag(p)
    p.set_defaults(handler=run)


def run(args) -> int:
    from ..records import json_ready, software
    from ..studies import doctor

    checks = make_with_runs(lambda _, runs: doctor.diagnose(runs), None, args.run_dir, "spinbounce-doctor-")
    summary, status = doctor.verdict({c.form.key: c.answer for c in checks})
    if args.json:
        rows = [{"form": c.form.key, "command": c.form.command, "omega_measured": c.measured,
                 "omega_paper": c.paper, "omega_contact_radius": c.contact_radius, "answer": c.answer}
                for c in checks]
        print_json(json_ready({"checks": rows, "verdict": summary, "exit_status": status,
                                "upstream": doctor.UPSTREAM, "software": software()}))
        return status
    print(f"LAMMPS {software()['lammps_version']}: Omega = u'(out)/u'(in) - 1 of one collision per form")
    print(f"{'form':40s} {'measured':>10s} {'paper':>10s} {'contact-r':>10s}  answer")
    for c in checks:
        print(f"{c.form.title:40s} {c.measured:10.6f} {c.paper:10.6f} {c.contact_radius:10.6f}  {c.answer}")
    print(f"verdict: {summary} (exit {status})")
    print(f"upstream: {doctor.UPSTREAM}")
    return status
