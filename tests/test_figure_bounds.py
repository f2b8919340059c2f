"""The figure-bounds check finds the text a saved figure cuts off, and only that.

The figure-bounds check (figure_bounds.texts_outside) finds text a saved figure cuts off,
and only that.
"""

import matplotlib.style

from figure_bounds import texts_outside
from spinbounce.figures.core import STYLE, new_figure


def _figure():
    with matplotlib.style.context(STYLE):
        fig, axes = new_figure(1, 2, figsize=(4.0, 2.0))
        for ax in axes[0]:
            ax.plot([0.0, 1.0], [0.0, 1.0])
            ax.set_xlabel("x")
            ax.set_ylabel("y")
    return fig


def test_a_laid_out_figure_has_no_text_outside():
    assert texts_outside(_figure()) == []


def test_text_past_any_edge_is_named_with_its_side():
    fig = _figure()
    fig.text(1.01, 0.5, "right", ha="left")
    fig.text(0.5, -0.02, "bottom", va="top")
    axes = fig.axes[0]
    axes.set_ylabel("a y-label far longer than these small axes are tall, so it runs past the figure")
    found = texts_outside(fig)
    assert len(found) == 3
    assert found[0].startswith("'a y-label far longer") and "beyond the top" in found[0]
    assert "beyond the bottom" in found[0]
    assert found[1].startswith("'right'") and "beyond the right" in found[1]
    assert found[2].startswith("'bottom'") and "beyond the bottom" in found[2]


def test_text_just_inside_the_edge_passes():
    fig = _figure()
    fig.text(0.999, 0.5, "x", ha="right")  # ends a few pixels inside the right edge
    assert texts_outside(fig) == []
