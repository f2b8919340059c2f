"""The compiled references are compiled once a machine, by one process, and their examples leave nothing to compile."""

import json
import os
import subprocess
import sys
import textwrap

import pytest

# Every family compiled by its example, then pair laws as users run them (the pair scene's own contact law, every
# reference path: the two compiled batches, the laws on the contact radius uncapped and capped, force histories,
# rescale, limit_damping, the classic spring's cap), each free and held, in one process on a cache of its own; the
# versions compiled after the examples are the examples' gaps (a shared cache could hold them from another process).
_LAWS = textwrap.dedent("""
    import json
    import numba
    import numpy as np
    from spinbounce.exact import first_use, pair_capped_batch
    from spinbounce.model.contact import ContactModel
    from spinbounce.scenes.pair.kind import pair_contact, pairs_from_states
    from spinbounce.scenes.pair.pairs import Sphere

    hm = dict(normal="hertz", tangential="mindlin", mindlin_kt=12.0)
    laws = [{}, {"mu": 0.3, "gamma_t": 1.0}, {"gamma_n": 2.0, "limit_damping": True}, {**hm, "gamma_n": 1.0},
            {**hm, "mu": 0.3, "gamma_n": 1.0, "gamma_t": 0.5}, {**hm, "tangential": "mindlin_rescale/force", "mu": 0.5},
            {"mu": 0.3, "tangential": "linear_history_classic"}, {**hm, "mu": 0.2, "damping": "tsuji", "e_n": 0.8}]
    states = np.array([[-0.8, 0.3, 0.2, 0.1, -0.2, 0.05], [-0.2, -0.1, 0.4, 0.0, 0.0, 0.0]])
    b = Sphere(1.0, 0.5, 0.4)

    def compiled():
        out = {}
        for name, module in __import__("sys").modules.items():
            if name.startswith("spinbounce.exact.") and not name.endswith("oracle_kernel"):
                for attr, value in vars(module).items():
                    if isinstance(value, numba.core.registry.CPUDispatcher):
                        out[f"{name}.{attr}"] = {str(sig) for sig in value._cache_misses}
        return out

    first_use.compile_all(log=lambda line: None)
    by_examples = compiled()
    for law in laws:
        model = ContactModel(wall="granular", **law)
        contact = pair_contact(model, b)
        for planar in (False, True):
            contact.solve_all(tuple(pairs_from_states(model, b, states)), planar)
    after = compiled()
    gaps = {name: sorted(sigs - by_examples.get(name, set())) for name, sigs in after.items()}
    print(json.dumps({"gaps": {k: v for k, v in gaps.items() if v}, "examples": sum(map(len, by_examples.values()))}))
""")


@pytest.mark.slow  # a cold cache: every family compiled again, about a minute of one core
def test_the_examples_compile_everything_a_pair_law_calls(tmp_path):
    """A compiled function a real solve calls with types its family's example never passed would compile outside
    the lock (exact.first_use): slow, and open to two processes writing the cache at once."""
    done = subprocess.run([sys.executable, "-c", _LAWS], capture_output=True, text=True, timeout=900,
                          env=_cold(tmp_path))
    assert done.returncode == 0, done.stderr[-3000:]
    found = json.loads(done.stdout.strip().splitlines()[-1])
    assert found["examples"] > 50, found  # the examples compiled the families here (each batch alone is ~20)
    assert found["gaps"] == {}, f"compiled outside their family's example: {found['gaps']}"


def _cold(folder) -> dict:
    """The environment with a cache folder of its own under ``folder`` (empty: nothing compiled)."""
    return {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"} | {"XDG_CACHE_HOME": str(folder)}


_ONCE = "from spinbounce.exact import first_use, pair_exact; first_use.once('pair'); print('solved')"


def test_two_processes_at_first_use_compile_once(tmp_path):
    """Two processes that need the same family on a cold cache: one compiles it, the other waits for it (or finds
    it done), and both go on; the marker then spares a third any note."""
    env = _cold(tmp_path)
    runs = [subprocess.Popen([sys.executable, "-c", _ONCE], env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             text=True) for _ in range(2)]
    outs = [run.communicate(timeout=300) for run in runs]
    assert [run.returncode for run in runs] == [0, 0], outs
    notes = "".join(err for _, err in outs)
    assert notes.count("compiling the pair reference") == 1, notes
    markers = list(tmp_path.glob("spinbounce-numba/*/compiled-pair-*"))
    assert len(markers) == 1
    third = subprocess.run([sys.executable, "-c", _ONCE], env=env, capture_output=True, text=True, timeout=300)
    assert third.returncode == 0 and third.stdout.strip() == "solved" and third.stderr == "", third.stderr


def test_an_example_that_fails_leaves_no_marker_and_says_so(tmp_path, monkeypatch):
    """An example's failure is no user's: its family compiles as it is used, and no marker claims it compiled."""
    from spinbounce.exact import first_use

    monkeypatch.setattr(first_use, "cache_folder", lambda: str(tmp_path))
    monkeypatch.setattr(first_use, "_READY", set())
    monkeypatch.setitem(first_use.EXAMPLES, "broken", (lambda: 1 / 0, 1.0))
    lines = []
    first_use.once("broken", log=lines.append)
    assert "compiling the broken reference ahead failed (division by zero)" in lines[-1], lines
    assert not list(tmp_path.glob("compiled-broken-*")) and list(tmp_path.glob("compiling.lock"))


_WHERE = "from spinbounce.exact import first_use, vec3; print(vec3.cache_folder()); print(first_use._machine())"


def test_a_process_waits_for_the_one_compiling_and_compiles_nothing_it_made(tmp_path):
    """While another process holds the lock, a process that needs the family says it waits; when the holder has
    written the marker and let go, it goes on without compiling (here the test itself holds the lock)."""
    import fcntl
    from pathlib import Path

    env = _cold(tmp_path)
    where = subprocess.run([sys.executable, "-c", _WHERE], env=env, capture_output=True, text=True, timeout=120)
    folder, machine = where.stdout.split()
    lock = os.open(Path(folder) / "compiling.lock", os.O_RDONLY | os.O_CREAT, 0o644)
    fcntl.flock(lock, fcntl.LOCK_EX)
    try:
        waiting = subprocess.Popen([sys.executable, "-c", _ONCE], env=env, stdout=subprocess.PIPE,
                                   stderr=subprocess.PIPE, text=True)
        first = waiting.stderr.readline()
        (Path(folder) / f"compiled-pair-{machine}").touch()
    finally:
        os.close(lock)
    out, rest = waiting.communicate(timeout=120)
    assert "waiting for another process compiling" in first, first + rest
    assert waiting.returncode == 0 and out.strip() == "solved" and "compiling the" not in rest, rest
