"""Text that a saved figure would cut off, found on any matplotlib Figure.

For any matplotlib Figure: every drawn text artist (titles, axis and tick labels, legend entries, annotations) whose extent, as the
figure's own canvas renderer lays it out, reaches beyond the figure's edges.

Used by tests of drawn figures: ``assert texts_outside(fig) == []``.
"""

from matplotlib.text import Text

#: Anti-aliasing and rounding of glyph extents: half a pixel at the figure's dpi.
TOLERANCE_PX = 0.5


def _undrawn_tick_labels(fig) -> set:
    """Labels of ticks outside their axis's view: matplotlib keeps but does not draw them."""
    skipped = set()
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            lo, hi = sorted(axis.get_view_interval())
            span = (hi - lo) * 1e-9
            for tick in [*axis.get_major_ticks(), *axis.get_minor_ticks()]:
                if not lo - span <= tick.get_loc() <= hi + span:
                    skipped |= {tick.label1, tick.label2}
    return skipped


def texts_outside(fig, tolerance_px: float = TOLERANCE_PX) -> list[str]:
    """One line per visible, non-empty text artist of ``fig`` that extends beyond its bounds.

    The figure is drawn first on its own canvas, which runs its layout engine as saving it
    (with the default ``bbox_inches=None``) does.
    """
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    bounds = fig.bbox
    skipped = _undrawn_tick_labels(fig)
    found = []
    for text in fig.findobj(Text):
        if not text.get_visible() or not text.get_text().strip() or text in skipped:
            continue
        box = text.get_window_extent(renderer)
        beyond = {"left": bounds.x0 - box.x0, "right": box.x1 - bounds.x1,
                  "bottom": bounds.y0 - box.y0, "top": box.y1 - bounds.y1}
        over = {side: px for side, px in beyond.items() if px > tolerance_px}
        if over:
            sides = ", ".join(f"{px:.1f} px beyond the {side}" for side, px in over.items())
            found.append(f"{text.get_text()!r}: {sides}")
    return found
