"""``rotorkin run`` imports only the drive it runs; figures drawn in parallel match serial."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from rotorkin import drives

SRC = str(Path(__file__).resolve().parents[1] / "src")


def _python(code: str, **env) -> subprocess.CompletedProcess:
    """Run ``code`` in a fresh interpreter with this checkout first on the path."""
    environ = {**os.environ, "PYTHONPATH": SRC + os.pathsep + os.environ.get("PYTHONPATH", ""),
               "MPLBACKEND": "Agg", **env}  # fmt: skip
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env=environ, timeout=300)  # fmt: skip


def _drive_packages(modules) -> set[str]:
    """The drive packages among imported module names."""
    parts = [m.split(".") for m in modules if m.startswith("rotorkin.drives.")]
    return {p[2] for p in parts if not p[2].startswith("_")}


def test_listing_drives_and_examples_imports_none():
    done = _python(
        "import json, sys\n"
        "from rotorkin import drives\n"
        "from rotorkin.io.config import example_names\n"
        "names, examples = drives.names(), example_names()\n"
        "print(json.dumps([names, examples, 'wobble_cam' in drives.REGISTRY, list(sys.modules)]))\n"
    )
    assert done.returncode == 0, done.stderr
    names, examples, contained, modules = json.loads(done.stdout)
    assert names == list(drives.BUILTIN)
    assert contained
    assert _drive_packages(modules) == set()
    # the same examples as the specs list once every drive is imported
    assert examples == sorted(e for s in drives.REGISTRY.values() for e in s.examples)


@pytest.mark.parametrize("kind", list(drives.BUILTIN))
def test_run_imports_only_the_running_drive(kind, tmp_path):
    example = drives.REGISTRY[kind].examples[0]
    done = _python(
        "import json, sys\n"
        "from rotorkin.cli import main\n"
        f"code = main(['run', '-e', {example!r}, '-o', {str(tmp_path / 'out')!r}, '-q', "
        "'--no-figures'])\n"
        "print(json.dumps([code, list(sys.modules)]))\n"
    )
    assert done.returncode == 0, done.stderr
    code, modules = json.loads(done.stdout.splitlines()[-1])
    assert code == 0
    assert _drive_packages(modules) == {kind}
    assert (tmp_path / "out" / "summary.json").is_file()


def test_registry_keeps_order_and_loads_on_access():
    registry = drives.Registry(("tabulated", "wobble_cam"))
    assert list(registry) == ["tabulated", "wobble_cam"] and len(registry) == 2
    spec = registry["tabulated"]
    assert spec.name == "tabulated" and registry.loaded("tabulated")
    assert registry.package("tabulated") is None
    assert registry.package("nothing") is None
    del registry["wobble_cam"]
    assert list(registry) == ["tabulated"]
    with pytest.raises(KeyError):
        registry["wobble_cam"]


def test_drive_package_as_attribute():
    assert drives.tabulated.SPEC is drives.REGISTRY["tabulated"]
    with pytest.raises(AttributeError):
        drives.no_such_drive  # noqa: B018
