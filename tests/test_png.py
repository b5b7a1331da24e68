"""The run's PNG files: encoded by rotorkin, read back by Pillow, equal to matplotlib's."""

from __future__ import annotations

import numpy as np
import pytest
from PIL import Image

from rotorkin.render import figures as F


@pytest.fixture()
def plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    yield plt
    plt.close("all")


def _figure(plt, dpi):
    fig, ax = plt.subplots(figsize=(6.3, 4.1), dpi=dpi)  # 4.1 x 120 = 491.99..: rounding
    ax.plot(np.sin(np.linspace(0, 10, 500)), lw=0.7)
    ax.fill_between([0, 100], [0, 0.5], alpha=0.3)
    ax.set_title("a title, and text to render: 0.123 [mm]")
    return fig


def test_png_has_matplotlibs_pixels(plt, tmp_path):
    fig = _figure(plt, F.DPI)
    F._write(fig, tmp_path / "ours.png", F.DPI)
    fig.savefig(tmp_path / "theirs.png", dpi=F.DPI)
    with Image.open(tmp_path / "ours.png") as im:
        im.verify()  # chunk CRCs and structure
    ours, theirs = Image.open(tmp_path / "ours.png"), Image.open(tmp_path / "theirs.png")
    assert ours.mode == "RGB" and ours.size == theirs.size == (756, 492)
    a, b = np.asarray(ours), np.asarray(theirs)
    assert np.all(b[..., 3] == 255)
    assert np.array_equal(a, b[..., :3])
    assert ours.info["Software"].startswith("matplotlib")


def test_png_at_another_resolution_is_written_by_matplotlib(plt, tmp_path):
    fig = _figure(plt, 72)
    F._write(fig, tmp_path / "a.png", 100)
    im = Image.open(tmp_path / "a.png")
    assert im.size == (630, 410)
    fig.savefig(tmp_path / "b.png", dpi=100)
    assert np.array_equal(np.asarray(im), np.asarray(Image.open(tmp_path / "b.png")))


def test_png_bytes_round_trip_with_and_without_transparency(tmp_path):
    rng = np.random.default_rng(3)
    rgba = rng.integers(0, 256, size=(7, 11, 4), dtype=np.uint8)
    (tmp_path / "t.png").write_bytes(F.png_bytes(rgba))
    im = Image.open(tmp_path / "t.png")
    assert im.mode == "RGBA" and np.array_equal(np.asarray(im), rgba)
    rgba[..., 3] = 255
    (tmp_path / "o.png").write_bytes(F.png_bytes(rgba, software="x"))
    im = Image.open(tmp_path / "o.png")
    assert im.mode == "RGB" and np.array_equal(np.asarray(im), rgba[..., :3])
    assert im.info["Software"] == "x"
