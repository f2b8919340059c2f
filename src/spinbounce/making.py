"""Making the catalogue's products: one after the other, or side by side on worker processes.

Side by side, the longest start first (:attr:`~spinbounce.catalogue.Product.seconds`) and each
worker takes the next when it is done; every product's log still reaches the caller whole and in
the catalogue's order (a product's lines are held until those before it are told), so that the
output reads as it does made in turn. What products share (a gas the claims and the gas figure
both show) is run by whichever gets there first while the other waits for it
(:func:`spinbounce.scenes.gas.run.shared_gas`). Only :data:`~spinbounce.catalogue.PRODUCTS` are
made side by side (a worker finds its product by name).

A product that fails is told at once, with the lines it logged before it failed; an interrupt or a
failure stops every worker (a worker that dies, too, ends the making with an error rather than a
wait), and their half-written files (``.NAME.PID.tmp``) are removed from the output folder; what
was written whole stays, as it does made in turn.
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


def _made(name: str, out: Path, runs: Path, force: bool) -> tuple[list[str], dict | None, float, Exception | None]:
    """One product, in a worker: (its log lines, its records, its seconds, what it failed with)."""
    from .outputs import replacing

    product = next(p for p in PRODUCTS if p.name == name)
    lines: list[str] = []
    began = time.perf_counter()
    try:
        with replacing(force):  # the parent's --force, which a worker's own context does not carry
            made = make(product, out, runs, log=lines.append)
    except Exception as failed:  # told with the lines before it (an interrupt is the parent's to answer)
        return lines, None, time.perf_counter() - began, failed
    return lines, made, time.perf_counter() - began, None


def _side_by_side(chosen: list[Product], out: Path, runs: Path, log, workers: int) -> dict[str, dict]:
    import concurrent.futures
    import multiprocessing
    import os

    from .outputs import forced
    from .workers import context, die_with_parent, main_unseen

    others = set(multiprocessing.active_children())  # this process's children that are not the pool's
    pool = concurrent.futures.ProcessPoolExecutor(workers, mp_context=context(), initializer=die_with_parent,
                                                  initargs=(os.getpid(),))
    try:
        with main_unseen():  # the workers start as the products are submitted
            pending = {p.name: pool.submit(_made, p.name, Path(out), Path(runs), forced())
                       for p in sorted(chosen, key=lambda p: -p.seconds)}
        records = _told_in_order(chosen, pending, Path(out), log)
    except BaseException:
        _stop(pool, [child for child in multiprocessing.active_children() if child not in others], Path(out))
        raise
    pool.shutdown()
    return records


def _told_in_order(chosen: list[Product], pending: dict, out: Path, log) -> dict[str, dict]:
    """Each product's log, whole, as soon as it and every one before it are done; a failure at once."""
    import concurrent.futures

    records: dict[str, dict] = {}
    told = 0
    while True:
        while told < len(chosen) and pending[chosen[told].name].done():
            product = chosen[told]
            lines, made, seconds, failed = pending[product.name].result()  # a worker that died raises here
            if failed is not None:
                break
            for line in [_opening(product, out), *lines, _closing(product, made, seconds)]:
                log(line)
            records.update(made)
            told += 1
        for product in chosen[told:]:  # a failure is told at once, after every product before it that ended
            future = pending[product.name]
            if future.done() and future.result()[3] is not None:
                lines, _, _, failed = future.result()
                for line in [_opening(product, out), *lines]:
                    log(line)
                raise failed
        if told == len(chosen):
            return records
        concurrent.futures.wait([f for f in pending.values() if not f.done()],
                                return_when=concurrent.futures.FIRST_COMPLETED)


def _stop(pool, children: list, out: Path) -> None:
    """Every worker (``children``) ended now, not when its product ends, and the files it was writing removed."""
    for child in children:
        child.terminate()
    for child in children:
        child.join(timeout=10.0)
    pool.shutdown(wait=False, cancel_futures=True)
    _remove_half_written(out, {str(child.pid) for child in children})


def _remove_half_written(out: Path, pids: set[str]) -> None:
    """The temporary files stopped workers left in ``out`` (``.NAME.PID.tmp``: only theirs)."""
    for path in out.rglob(f".*{TEMP_SUFFIX}"):
        if path.name.removesuffix(TEMP_SUFFIX).rsplit(".", 1)[-1] in pids:
            path.unlink(missing_ok=True)
