"""The package: the core install works without the optional extras, a missing extra is one
line naming its pip command, the extras in pyproject.toml are the ones the command line
names, and the version is written in one place."""

from __future__ import annotations

import json
import re
import subprocess
import sys
import textwrap
import tomllib
from pathlib import Path

import numpy as np
import pytest

import rotorkin
from rotorkin.cli import EXTRAS, main

ROOT = Path(__file__).resolve().parents[1]
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())

#: The modules of the optional extras, made absent in the subprocesses below.
OPTIONAL = sorted(EXTRAS)

#: A subprocess's prelude: every optional module absent (an import of it, or of anything
#: below it, raises ModuleNotFoundError; importlib.util.find_spec answers None), as in an
#: environment where only the core is installed.
BLOCK = textwrap.dedent(f"""
    import sys

    class Absent:
        '''A finder that makes the optional modules absent.'''
        names = {OPTIONAL!r}

        def find_spec(self, name, path=None, target=None):
            if name.split(".")[0] in self.names:
                raise ModuleNotFoundError(f"No module named {{name!r}}", name=name)
            return None

    for name in Absent.names:
        sys.modules[name] = None  # find_spec(name) is None: the probes see it absent
    sys.meta_path.insert(0, Absent())
""")


def _python(code: str, cwd: Path, timeout: float = 300) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", BLOCK + textwrap.dedent(code)], cwd=cwd,
                          capture_output=True, text=True, timeout=timeout)  # fmt: skip


def test_the_blocker_blocks(tmp_path):
    """The prelude really hides the extras (else the tests below would prove nothing)."""
    proc = _python(
        """
        import importlib, importlib.util
        for name in Absent.names:
            assert importlib.util.find_spec(name) is None, name
            try:
                importlib.import_module(name)
            except ModuleNotFoundError as exc:
                assert exc.name == name
            else:
                raise AssertionError(name)
        print("blocked", len(Absent.names))
        """,
        tmp_path,
    )
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.split() == ["blocked", str(len(OPTIONAL))]


def test_every_module_imports_and_run_works_without_the_extras(tmp_path):
    """Every module of the package imports, and ``run`` (every example) and the Python API
    work, with plotly, the CAD libraries, dask, Cantera and pymoo absent."""
    proc = _python(
        """
        import importlib, json, pkgutil
        import numpy as np
        import rotorkin
        from rotorkin.cli import main

        names = [m.name for m in pkgutil.walk_packages(rotorkin.__path__, "rotorkin.")
                 if not m.name.endswith("__main__")]
        for name in names:
            importlib.import_module(name)
        from rotorkin.io.config import example_names
        codes = {e: main(["run", "-e", e, "--no-figures", "-q", "--out", e])
                 for e in example_names()}
        from rotorkin.drives.wobble_cam import kinematics as wc
        m = wc.motion(wc.WobbleCam(plate_tilt=np.radians(45), roller_axis_angle=np.radians(90)),
                      np.linspace(0, 2 * np.pi, 9))
        absent = sorted(n for n in Absent.names if sys.modules.get(n) is not None)
        print(json.dumps({"modules": len(names), "codes": codes, "absent_loaded": absent,
                          "shape": list(np.shape(m.q))}))
        """,
        tmp_path,
    )
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(proc.stdout.strip().splitlines()[-1])
    assert doc["modules"] > 100 and doc["absent_loaded"] == []
    assert doc["codes"] and set(doc["codes"].values()) == {0}, proc.stderr
    reference = json.loads((Path(__file__).parent / "data/reference_outputs.json").read_text())
    for example in doc["codes"]:
        summary = json.loads((tmp_path / example / "summary.json").read_text())
        assert summary["name"] == example
        # the same numbers as with every extra installed (the NASA gas needs no Cantera)
        ref = reference[example]["summary"]
        assert summary.get("gas_properties") == ref.get("gas_properties"), example
        for key in ("peak_pressure_bar", "indicated_work_J"):
            if key in ref:
                assert summary[key] == pytest.approx(ref[key], rel=1e-9), (example, key)
    assert doc["shape"][-1] == 9


def test_run_draws_its_figures_without_the_extras(tmp_path):
    proc = _python(
        """
        from rotorkin.cli import main
        raise SystemExit(main(["run", "-e", "eccentric-reactor", "-q", "--out", "o"]))
        """,
        tmp_path,
    )
    assert proc.returncode == 0, proc.stderr
    assert len(list((tmp_path / "o").glob("*.png"))) >= 3


def test_the_core_commands_work_without_xarray_and_pandas(tmp_path):
    """sweep (netCDF, overview, README), limits, solve, tolerance and run on the core install:
    xarray and pandas absent (as every extra); the files read back with xarray here."""
    proc = _python(
        """
        import contextlib, io, json
        from rotorkin.cli import main
        commands = {
            "sweep": ["sweep", "--vary", "drive.plate_tilt=30deg:40deg:3",
                      "--vary", "machine.section=rectangular,circular", "--curves", "-q",
                      "--out", "sw"],
            "limits": ["limits", "--key", "drive.plate_tilt", "--format", "json"],
            "solve": ["solve", "-e", "guide-bar-pump", "--for", "drive.lambda", "--target",
                      "flow_mean_l_per_min=20", "--format", "json"],
            "tolerance": ["tolerance", "--tol", "drive.plate_tilt=0.1deg", "--samples", "50",
                          "--angles", "361", "-q", "--out", "tol"],
            "run": ["run", "-e", "guide-bar-pump", "-q", "--out", "run"],
        }
        answers = {}
        for name, args in commands.items():
            out, err = io.StringIO(), io.StringIO()
            with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
                code = main(args)
            answers[name] = (code, out.getvalue(), err.getvalue())
        loaded = sorted(n for n in Absent.names if sys.modules.get(n) is not None)
        print(json.dumps({"answers": answers, "loaded": loaded}))
        """,
        tmp_path,
    )
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(proc.stdout.strip().splitlines()[-1])
    assert doc["loaded"] == []
    for name, (code, _, err) in doc["answers"].items():
        assert code == 0, (name, err)
    limits = json.loads(doc["answers"]["limits"][1])
    assert limits["key"] == "drive.plate_tilt" and limits["lo"] < limits["value"] < limits["hi"]
    solved = json.loads(doc["answers"]["solve"][1])
    assert abs(solved["reached"] - 20.0) <= 1e-6 * 20.0
    assert {p.name for p in (tmp_path / "sw").iterdir() if p.name[0] != "."} == {
        "sweep.nc", "sweep_overview.png", "README.txt"}  # fmt: skip
    assert (tmp_path / "run" / "summary.json").is_file()
    import xarray as xr

    with xr.open_dataset(tmp_path / "sw" / "sweep.nc") as ds:
        assert ds.sizes == {"drive.plate_tilt": 3, "machine.section": 2, "point": 721}
        assert list(ds["machine.section"].values) == ["rectangular", "circular"]
        assert ds["reason"].dtype == np.int16 and ds.attrs["designs"] == 6
    with xr.open_dataset(tmp_path / "tol" / "tolerance.nc") as ds:
        assert ds.sizes == {"sample": 50} and ds.attrs["samples"] == 50


def test_the_python_api_names_the_xarray_extra(tmp_path):
    """Without xarray the functions that return Datasets raise one line naming the extra,
    before any work."""
    proc = _python(
        """
        import json
        from rotorkin.io.config import load_config
        from rotorkin.sweep import build_spec, compute, execute, run_sweep
        from rotorkin.tolerance import run_tolerance
        from rotorkin.drives import evaluate

        cfg, raw, _ = load_config()
        spec = build_spec(raw, {"drive.plate_tilt": "30deg:40deg:2"})
        calls = {
            "run_sweep": lambda: run_sweep(raw, {"drive.plate_tilt": "30deg:40deg:2"}),
            "execute": lambda: execute(spec),
            "run_tolerance": lambda: run_tolerance(raw, ["drive.plate_tilt=0.1deg"]),
            "to_xarray": lambda: evaluate(cfg).to_xarray(),
            "to_dataframe": lambda: evaluate(cfg).to_dataframe(),
        }
        out = {}
        for name, call in calls.items():
            try:
                call()
            except ModuleNotFoundError as exc:
                out[name] = [exc.name, str(exc)]
        out["compute"] = int(compute(spec, progress=False).attrs["designs"])
        print(json.dumps(out))
        """,
        tmp_path,
    )
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(proc.stdout.strip().splitlines()[-1])
    assert doc.pop("compute") == 2
    assert set(doc) == {"run_sweep", "execute", "run_tolerance", "to_xarray", "to_dataframe"}
    for name, (module, message) in doc.items():
        assert module == "xarray", name
        assert "\n" not in message and 'pip install "rotorkin[xarray]"' in message, message
        assert message.endswith("(xarray is not installed)")


#: Commands whose extra is absent: (arguments, the extra, the module named).
MISSING = [
    (["report", "-e", "rhomboid-engine"], "report", "plotly"),
    (["run", "-e", "guide-bar-pump", "--report"], "report", "plotly"),
    (["export", "-e", "guide-bar-pump", "-f", "dxf"], "cad", "ezdxf"),
    (["export", "-e", "wobble-cam-engine", "-f", "stl"], "cad", "trimesh"),
    (["export", "-e", "rhomboid-engine", "-f", "step"], "cad", "build123d"),
    (["export", "-e", "rhomboid-engine", "-f", "all"], "cad", "ezdxf"),
    (["sweep", "--vary", "drive.plate_tilt=30deg:40deg:3", "--workers", "2"], "dask", "dask"),
    (["optimize", "-e", "guide-bar-pump", "--vary", "drive.lambda=0.1:0.8", "--objective",
      "max:flow_mean_l_per_min"], "optimize", "pymoo"),
]  # fmt: skip


@pytest.fixture(scope="module")
def refusals(tmp_path_factory):
    """Each MISSING command run in one subprocess without the extras: (code, out, err)."""
    folder = tmp_path_factory.mktemp("missing")
    proc = _python(
        f"""
        import contextlib, io, json
        from rotorkin.cli import main
        answers = []
        for args in {[[*args, "--out", "out"] for args, _, _ in MISSING]!r}:
            out, err = io.StringIO(), io.StringIO()
            with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
                code = main(args)
            answers.append((code, out.getvalue(), err.getvalue()))
        print(json.dumps(answers))
        """,
        folder,
    )
    assert proc.returncode == 0, proc.stderr
    return folder, json.loads(proc.stdout)


@pytest.mark.parametrize("case", range(len(MISSING)))
def test_a_missing_extra_is_one_line_naming_its_pip_command(case, refusals):
    folder, answers = refusals
    args, extra, module = MISSING[case]
    code, out, err = answers[case]
    assert code == 2 and out == ""
    assert err.splitlines() == [
        f'rotorkin: error: rotorkin {args[0]} needs the {extra} extra: pip install '
        f'"rotorkin[{extra}]" ({module} is not installed)'
    ]  # fmt: skip
    assert list(folder.iterdir()) == []  # refused before any work: nothing written


def test_a_missing_module_deep_in_a_command_names_its_extra(tmp_path, capsys, monkeypatch):
    """An extra imported where no command checked for it still ends in the one line."""
    import rotorkin.cli.run as run_module

    def evaluate(cfg):
        raise ModuleNotFoundError("No module named 'trimesh.creation'", name="trimesh.creation")

    monkeypatch.setattr(run_module, "evaluate", evaluate)
    assert main(["run", "-o", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert err == ('rotorkin: error: rotorkin run needs the cad extra: pip install '
                   '"rotorkin[cad]" (trimesh is not installed)\n')  # fmt: skip
    # a module that no extra provides is an internal error, not an install hint
    monkeypatch.setattr(run_module, "evaluate", lambda cfg: __import__("no_such_module_xyz"))
    assert main(["run", "-o", str(tmp_path / "p")]) == 1
    assert "internal error: ModuleNotFoundError" in capsys.readouterr().err


def _requirement_names(requirements) -> set[str]:
    return {re.split(r"[<>=\[; ]", r, maxsplit=1)[0].lower() for r in requirements}


#: The distribution that provides an importable module, where the names differ.
DISTRIBUTION = {"OCP": "build123d", "distributed": "dask", "pandas": "xarray"}


def test_the_extras_are_the_ones_the_command_line_names():
    extras = PYPROJECT["project"]["optional-dependencies"]
    core = _requirement_names(PYPROJECT["project"]["dependencies"])
    for module, extra in EXTRAS.items():
        dist = DISTRIBUTION.get(module, module).lower()
        assert dist in _requirement_names(extras[extra]), (module, extra)
        assert dist not in core, module  # the core install leaves it out
    # "docs" (the API reference's Sphinx) and "test" are for developers, not the commands
    assert set(EXTRAS.values()) | {"all", "test", "docs"} == set(extras)
    everything = {e for r in extras["all"] for e in re.findall(r"\[(.*)\]", r)[0].split(",")}
    assert everything == set(extras) - {"all", "test", "docs"}
    # the tests run every extra's code but STEP (build123d, installed by CI's script)
    test = extras["test"]
    named = {e for r in test if r.startswith("rotorkin[") for e in r[9:-1].split(",")}
    covered = {m for m, e in EXTRAS.items() if e in named} | {
        m for m in EXTRAS if DISTRIBUTION.get(m, m).lower() in _requirement_names(test)
    }
    assert set(EXTRAS) - covered == {"build123d", "OCP"}


def test_the_core_holds_what_run_and_sweep_import():
    core = _requirement_names(PYPROJECT["project"]["dependencies"])
    assert core == {"numpy", "scipy", "matplotlib", "typer", "rich", "pydantic", "pint"}


def test_the_version_is_written_once():
    project = PYPROJECT["project"]
    assert "version" not in project and "version" in project["dynamic"]
    attr = PYPROJECT["tool"]["setuptools"]["dynamic"]["version"]["attr"]
    assert attr == "rotorkin.__version__"
    assert re.fullmatch(r"\d+\.\d+\.\d+", rotorkin.__version__)
    changelog = (ROOT / "CHANGELOG.md").read_text()
    assert f"## [{rotorkin.__version__}]" in changelog and "## [Unreleased]" in changelog


def test_version_flag_prints_it(capsys):
    assert main(["--version"]) == 0
    assert capsys.readouterr().out == f"rotorkin {rotorkin.__version__}\n"


def test_the_sdist_manifest_carries_the_docs():
    manifest = (ROOT / "MANIFEST.in").read_text().split("\n")
    assert "graft docs" in manifest and "graft tests" in manifest
    assert any(line.startswith("include") and "CHANGELOG.md" in line for line in manifest)
