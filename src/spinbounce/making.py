"""Making the catalogue's products: one after the other, or side by side on worker processes.

Side by side, the longest start first (:attr:`~spinbounce.catalogue.Product.seconds`) and each
worker takes the next when it is done; every product's log still reaches the caller whole and in
the catalogue's order (a product's lines are held until those before it are told), so that the
output reads as it does made in turn. What products share (a gas the claims and the gas figure
both show) is run by whichever gets there first while the other waits for it
(:func:`spinbounce.scenes.gas.run.shared_gas`).

An interrupt or a failure stops every worker at once: their half-written files (``.NAME.PID.tmp``)
are removed from the output folder; what was written whole stays, as it does made in turn.
"""

from __future__ import annotations

import time
from pathlib import Path

from .catalogue import PRODUCTS, Product, make
from .records import TEMP_SUFFIX

__all__ = ["make_products"]


def make_products(chosen: list[Product], out: Path, runs: Path, log=print, workers: int = 1) -> dict[str, dict]:
    """Make ``chosen`` into ``out`` (LAMMPS runs under ``runs``) on ``workers`` processes (1: in
    this one); each product's log opens with what it makes and closes with its records and time.
    Returns every record by name."""
    workers = max(1, min(int(workers), len(chosen)))
    if workers == 1:
        return _in_turn(chosen, out, runs, log)
    return _side_by_side(chosen, out, runs, log, workers)


def _opening(product: Product, out: Path) -> str:
    return f"{product.name}: {product.what} -> {out}/"


def _closing(product: Product, made: dict, seconds: float) -> str:
    return f"{product.name}: {', '.join(sorted(made))} ({seconds:.0f} s)"


def _in_turn(chosen: list[Product], out: Path, runs: Path, log) -> dict[str, dict]:
    records: dict[str, dict] = {}
    for product in chosen:
        log(_opening(product, out))
        began = time.perf_counter()
        made = make(product, out, runs, log=log)
        records.update(made)
        log(_closing(product, made, time.perf_counter() - began))
    return records


def _made(name: str, out: Path, runs: Path, force: bool) -> tuple[list[str], dict, float]:
    """One product, in a worker: (its log lines, its records, its seconds)."""
    from .outputs import replacing

    product = next(p for p in PRODUCTS if p.name == name)
    lines: list[str] = []
    began = time.perf_counter()
    with replacing(force):  # the parent's --force, which a worker's own context does not carry
        made = make(product, out, runs, log=lines.append)
    return lines, made, time.perf_counter() - began


def _side_by_side(chosen: list[Product], out: Path, runs: Path, log, workers: int) -> dict[str, dict]:
    import multiprocessing

    from .outputs import forced
    from .workers import context, die_with_parent

    records: dict[str, dict] = {}
    pool = context().Pool(workers, initializer=die_with_parent)
    try:
        longest_first = sorted(chosen, key=lambda p: -p.seconds)
        pending = {p.name: pool.apply_async(_made, (p.name, Path(out), Path(runs), forced())) for p in longest_first}
        for product in chosen:
            lines, made, seconds = pending[product.name].get()
            for line in [_opening(product, out), *lines, _closing(product, made, seconds)]:
                log(line)
            records.update(made)
        pool.close()
    except BaseException:
        stopped = {str(child.pid) for child in multiprocessing.active_children()}
        pool.terminate()
        _remove_half_written(Path(out), stopped)
        raise
    finally:
        pool.join()
    return records


def _remove_half_written(out: Path, pids: set[str]) -> None:
    """The temporary files stopped workers left in ``out`` (``.NAME.PID.tmp``: only theirs)."""
    for path in out.rglob(f".*{TEMP_SUFFIX}"):
        if path.name.removesuffix(TEMP_SUFFIX).rsplit(".", 1)[-1] in pids:
            path.unlink(missing_ok=True)
