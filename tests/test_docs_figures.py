"""Every figure of docs/img comes from ``docs/make_figures.py``, and drawing one again gives it."""

from __future__ import annotations

import importlib.util
import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
IMG = ROOT / "docs" / "img"


def _script():
    spec = importlib.util.spec_from_file_location("make_figures", ROOT / "docs/make_figures.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_script_writes_exactly_the_files_of_docs_img():
    assert set(_script().FIGURES) == {p.name for p in IMG.iterdir()}


def test_every_figure_is_shown_by_a_document():
    texts = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]
    shown = {m for p in texts for m in re.findall(r"img/([\w.-]+\.png)", p.read_text())}
    assert shown == set(_script().FIGURES)


def _png_size(path: Path) -> tuple[int, int]:
    head = path.read_bytes()[:24]
    assert head[:8] == b"\x89PNG\r\n\x1a\n", f"{path} is not a PNG"
    return int.from_bytes(head[16:20], "big"), int.from_bytes(head[20:24], "big")


@pytest.mark.slow
def test_a_figure_drawn_again_is_the_committed_one(tmp_path):
    import matplotlib.image as mpimg

    name = "wobble_chamber_angle.png"
    # in a process of its own, as a user runs it (matplotlib's state of this one aside)
    out = subprocess.run([sys.executable, str(ROOT / "docs/make_figures.py"), "--only", name,
                          "--out", str(tmp_path)], capture_output=True, text=True, check=True,
                         env={**os.environ, "PYTHONPATH": str(ROOT / "src")})  # fmt: skip
    drawn = Path(out.stdout.strip())
    assert drawn == tmp_path / name
    assert _png_size(drawn) == _png_size(IMG / name)
    new, old = mpimg.imread(drawn)[..., :3], mpimg.imread(IMG / name)[..., :3]
    assert new.shape == old.shape
    ink = np.mean(np.any(old < 0.9, axis=-1))  # share of pixels that are not (near) white
    assert ink > 0.02, "the committed figure is (almost) blank"
    # the same curves, labels and ticks: few pixels differ (font rendering may)
    differ = np.mean(np.any(np.abs(new - old) > 0.25, axis=-1))
    assert differ < 0.1 * ink, f"{differ:.2%} of the pixels differ ({ink:.2%} inked)"


def test_an_unknown_figure_is_refused(tmp_path):
    with pytest.raises(SystemExit, match="unknown figure"):
        _script().make(["nope.png"], tmp_path)
