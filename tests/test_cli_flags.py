"""The library names its parameters; the command line names the flag the user typed."""

from __future__ import annotations

import pytest

from rotorkin.cli import main
from rotorkin.core.errors import ParameterError
from rotorkin.io.config import load_config
from rotorkin.sweep import build_spec


def test_the_library_names_its_parameter():
    _, raw, _ = load_config()
    with pytest.raises(ParameterError) as err:
        build_spec(raw, ["drive.plate_tilt=30deg:40deg:3"], samples=2)
    assert err.value.name == "samples" and "--" not in str(err.value)


@pytest.mark.parametrize(
    ("args", "line"),
    [
        (["sweep", "--vary", "drive.plate_tilt=30deg:40deg:3", "--angles", "2"],
         "--angles = 2 is not admissible: 3 <= --angles <= 1000001"),
        (["sweep", "--vary", "drive.plate_tilt=30deg:40deg:3", "--chunk", "0"],
         "--chunk = 0 is not admissible: --chunk >= 1"),
        (["tolerance", "--tol", "drive.plate_tilt=0.1deg", "--samples", "1"],
         "--samples = 1 is not admissible: 2 <= --samples <= 10000000"),
        (["tolerance", "--tol", "drive.plate_tilt=0.1deg", "--angles", "0"],
         "--angles = 0 is not admissible: 3 <= --angles <= 1000001"),
        (["synthesize", "--objective", "nope"], "--objective = 'nope' is not admissible"),
    ],
)  # fmt: skip
def test_the_command_names_the_flag(args, line, tmp_path, capsys):
    assert main([*args, "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and line in err[0]
    assert not (tmp_path / "o").exists()
