"""The API reference builds from the docstrings with every warning an error.

``docs/conf.py`` and the pages of ``docs/api/`` are built by Sphinx (autodoc +
numpydoc) into a temporary folder with ``-W``: a docstring that does not render
(a broken numpydoc section, bad reStructuredText, an ambiguous cross-reference)
fails the build. The tools come with the ``docs`` extra (also in ``test``).
"""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

from rotorkin import drives

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"

#: What the reference must document, by the anchor Sphinx writes for it.
REQUIRED = (
    "rotorkin.core.motion.Motion",
    "rotorkin.core.errors.ParameterError",
    "rotorkin.drives.evaluate",
    "rotorkin.drives.design_checks",
    "rotorkin.drives.spec_of",
    "rotorkin.drives.DriveSpec",
    "rotorkin.sweep.build_spec",
    "rotorkin.sweep.execute",
    "rotorkin.sweep.run_sweep",
    "rotorkin.sweep.checks.check_metrics",
    "rotorkin.studies.checks.Check",
    "rotorkin.studies.StudyResult",
    "rotorkin.design.solve",
    "rotorkin.design.optimize.optimize",
    "rotorkin.analysis.torque",
    "rotorkin.machines.twin_rotor",
    "rotorkin.cams.planar",
    "rotorkin.io.config.load_config",
    "rotorkin.io.export.export",
    "rotorkin.render.workshop",
)


def _automodules() -> set[str]:
    pages = [DOCS / "index.rst", *sorted((DOCS / "api").glob("*.rst"))]
    found = set()
    for page in pages:
        found.update(re.findall(r"^\.\. automodule:: (\S+)", page.read_text(), re.M))
    return found


def test_every_registered_drive_has_its_kinematics_in_the_reference():
    documented = _automodules()
    for name, spec in drives.REGISTRY.items():
        package = f"rotorkin.drives.{name}"
        assert package in documented, f"{package} has no page in docs/api"
        own = {m for m in documented if m.startswith(package + ".")}
        assert own, f"none of {package}'s modules is documented"
        assert spec.name == name


@pytest.mark.slow
def test_api_reference_builds_without_a_warning(tmp_path):
    out = tmp_path / "html"
    cmd = [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html",
           "-d", str(tmp_path / "doctrees"), str(DOCS), str(out)]  # fmt: skip
    proc = subprocess.run(cmd, capture_output=True, text=True, cwd=tmp_path, timeout=600)
    log = proc.stdout + proc.stderr
    assert proc.returncode == 0, f"sphinx-build failed:\n{log}"
    assert "WARNING" not in log and "ERROR" not in log, log
    html = "".join(p.read_text(encoding="utf-8") for p in out.rglob("*.html"))
    anchors = set(re.findall(r'id="(?:module-)?(rotorkin[\w.]*)"', html))
    missing = [name for name in REQUIRED if name not in anchors]
    assert not missing, f"not in the built reference: {missing}"
    # numpydoc rendered the sections as field lists (plain autodoc would leave the text)
    assert ">Parameters<" in html and 'class="field-list' in html
    # nothing was written into the source tree
    assert not (DOCS / "_build").exists()
