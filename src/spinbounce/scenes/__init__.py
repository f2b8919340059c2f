"""Every scene spinbounce runs, one folder each: the wall collision, the frozen contact, the
pair of free spheres and the sphere between two walls.

A folder holds the scene's class (``scene.py``: pure data, checked when built, so bad input
is refused before LAMMPS starts), its deck and template (``deck.py``, ``*.lmp.j2``), its
table of LAMMPS's output beside the references (``table.py``) and ``theory.md``, the
equations it is checked against (two walls: one module, its template and ``theory.md``). The
scene calls its deck and table, never the other way round; importing this package imports none.

A scene whose rows are collisions (``collision``, ``pair``) answers what :func:`~spinbounce.pipeline.run_scene` and the step
probe (:func:`~spinbounce.stepping.tune`) ask: ``kind``, ``n``, ``dt``, ``nsteps``,
``default_step``; ``render(atoms)``, ``read(info, deck, folder)`` (the checked table's
columns), ``row_states(columns)`` (what :mod:`spinbounce.checks` measures), ``record(deck)``
(its parameters for the provenance); ``needs_probe()``, ``probe_time(sample)``,
``first_probe_steps(t)``, ``step_limit(t)``, ``fallback()``, ``beyond_reach()``, ``rows(index)`` and
``at_step(dt)``. A time-series scene (``frozen``) answers ``kind``, ``render()``, ``read(...)``,
``record()`` and ``max_abs_error(table)`` for :func:`~spinbounce.pipeline.run_series`; two walls
runs itself (:func:`~spinbounce.scenes.two_walls.run_two_walls`) on the same deck writer and runner.
"""
