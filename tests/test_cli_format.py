"""What the commands print: --format json/csv at full precision, --quiet, --verbose, tables
on a pipe, the help (option types, completion, the command list) and the lazy command list."""

from __future__ import annotations

import ast
import csv
import io
import json
import math
import os
import subprocess
import sys

import pytest

from rotorkin.cli import COMMANDS, app, main
from rotorkin.drives import evaluate
from rotorkin.io.config import load_config

#: The pump with no pressure to lift: three summary values have no meaning (NaN).
LIFTS_NOTHING = ("guide-bar-pump", "loads.discharge_pressure=1 bar")


def _summary(example: str, *sets: str) -> dict:
    """The study's own summary, computed here (not read from the command's output)."""
    return evaluate(load_config(None, example, list(sets))[0]).summary


def _run(capsys, *args):
    code = main(list(args))
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def _set_args(sets):
    return [a for s in sets for a in ("--set", s)]


@pytest.mark.parametrize(
    ("example", "sets"), [("wobble-cam-engine", ()), (LIFTS_NOTHING[0], LIFTS_NOTHING[1:])]
)
def test_run_json_is_every_summary_value_at_full_precision(example, sets, tmp_path, capsys):
    code, out, err = _run(capsys, "run", "-e", example, *_set_args(sets), "--no-figures",
                          "--format", "json", "--out", str(tmp_path))  # fmt: skip
    assert code == 0, err
    doc = json.loads(out, parse_constant=lambda c: pytest.fail(f"{c} in strict JSON"))
    summary = _summary(example, *sets)
    assert list(doc["summary"]) == list(summary)
    for key, value in summary.items():
        if isinstance(value, float) and not math.isfinite(value):
            assert doc["summary"][key] is None, key
        else:  # the same number, bit for bit, and an integer stays an integer
            shown = doc["summary"][key]
            assert shown == value and isinstance(shown, float) == isinstance(value, float), key
    assert doc["name"] == example and doc["out"] == str(tmp_path)
    assert set(doc["files"]) == {p.name for p in tmp_path.iterdir() if p.name[0] != "."}
    assert not any(f.endswith(".png") for f in doc["files"])  # --no-figures
    # the checks as records: margin = limit - value for an upper limit
    for c in doc["checks"]:
        if c["value"] is not None and c["limit"] is not None:
            sign = 1.0 if c["upper"] else -1.0
            assert c["margin"] == pytest.approx(sign * (c["limit"] - c["value"]), abs=1e-12)
            assert c["passed"] == (c["margin"] >= 0)
    if sets:  # a value without meaning is null in JSON and left out of summary.json
        undefined = {k for k, v in doc["summary"].items() if v is None}
        written = json.loads((tmp_path / "summary.json").read_text())
        assert undefined and undefined == set(written["undefined"])


@pytest.mark.parametrize(
    ("example", "sets"), [("eccentric-reactor", ()), (LIFTS_NOTHING[0], LIFTS_NOTHING[1:])]
)
def test_run_csv_reads_back_to_the_summary(example, sets, tmp_path, capsys):
    code, out, err = _run(capsys, "run", "-e", example, *_set_args(sets), "--no-figures",
                          "--format", "csv", "-o", str(tmp_path))  # fmt: skip
    assert code == 0, err
    rows = list(csv.DictReader(io.StringIO(out)))
    summary = _summary(example, *sets)
    assert [r["metric"] for r in rows] == list(summary)
    headline = evaluate(load_config(None, example, list(sets))[0]).headline
    for row in rows:
        value = summary[row["metric"]]
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            assert row["value"] == str(value)
        elif isinstance(value, float) and not math.isfinite(value):
            assert row["value"] == ""
        else:
            assert type(value)(row["value"]) == value  # the same float, bit for bit
        assert row["meaning"] == (headline.get(row["metric"], "") if isinstance(headline, dict)
                                  else "")  # fmt: skip


def test_limits_json_csv_and_the_old_json_flag_agree(capsys):
    args = ["limits", "-e", "eccentric-reactor", "--key", "drive.eccentricity", "--points", "21"]
    outs = {}
    for extra in (["--json"], ["--format", "json"], ["--format", "csv"], []):
        code, outs[" ".join(extra)], err = _run(capsys, *args, *extra)
        assert code == 0, err
    doc = json.loads(outs["--json"])
    assert doc == json.loads(outs["--format json"])
    rows = dict(csv.reader(io.StringIO(outs["--format csv"])))
    assert rows.pop("field") == "value"
    assert float(rows["hi"]) == doc["hi"] and float(rows["lo"]) == doc["lo"]
    assert float(rows["intervals[0][1]"]) == doc["intervals"][0][1]
    assert doc["key"] == "drive.eccentricity" and doc["lo"] < doc["value"] == 40.0 < doc["hi"]
    assert f"to {doc['hi']:.10g} mm" in outs[""] and doc["unit"] == "mm"


def test_solve_json_is_the_record_it_writes(tmp_path, capsys):
    args = ["solve", "-e", "guide-bar-pump", "--for", "machine.casing_radius", "--target",
            "flow_mean_l_per_min=20", "--set", 'run.speed="1500 rpm"']  # fmt: skip
    code, out, err = _run(capsys, *args, "--format", "json", "--out", str(tmp_path / "s"))
    assert code == 0, err
    doc = json.loads(out)
    written = json.loads((tmp_path / "s" / "solve.json").read_text())
    assert {k: doc[k] for k in written} == written and doc["files"] == ["config.toml", "solve.json"]
    code, out, err = _run(capsys, *args, "--format", "csv")
    assert code == 0, err
    rows = dict(csv.reader(io.StringIO(out)))
    assert float(rows["value"]) == doc["value"] and float(rows["reached"]) == doc["reached"]
    assert rows["lower_end.source"] == doc["lower_end"]["source"]
    # the solved radius gives the target flow (the library's own check, within its tolerance)
    assert doc["reached"] == pytest.approx(20.0, rel=1e-6)


def test_bad_format_is_one_line_exit_2(tmp_path, capsys):
    code, out, err = _run(capsys, "run", "--format", "xml", "-o", str(tmp_path / "o"))
    assert code == 2 and out == ""
    assert err.strip().splitlines() == [
        "rotorkin: error: --format = 'xml' is not admissible: one of table, json, csv"
    ]
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize(
    "args",
    [
        ["run", "--no-figures"],
        ["run", "--no-figures", "--format", "json"],
        ["examples"],
        ["keys", "wobble_cam"],
        ["limits", "-e", "eccentric-reactor", "--key", "drive.eccentricity", "--points", "21"],
        ["export", "-e", "rhomboid-engine", "-f", "csv"],
        ["compare", "-e", "wobble-cam-engine", "--drive", "noncircular_gears"],
    ],
)
def test_quiet_prints_nothing_on_stdout(args, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, out, err = _run(capsys, *args, "--quiet")
    assert code == 0, err
    assert out == ""
    assert all(line.startswith("rotorkin: warning: ") for line in err.splitlines())


def test_report_has_quiet(tmp_path, capsys):
    pytest.importorskip("plotly", reason="the report needs the [report] extra")
    code, out, err = _run(capsys, "report", "-e", "eccentric-reactor", "-q", "-o", str(tmp_path))
    assert code == 0 and out == "" and err == ""
    assert (tmp_path / "report.html").stat().st_size > 100_000


def test_quiet_and_verbose_together_are_refused(capsys):
    code, out, err = _run(capsys, "examples", "--quiet", "--verbose")
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and "either --quiet or --verbose" in err


def test_verbose_says_each_step_and_its_time_on_stderr(tmp_path, capsys):
    code, out, err = _run(capsys, "run", "--no-figures", "-v", "-o", str(tmp_path))
    assert code == 0
    steps = [ln for ln in err.splitlines() if not ln.startswith("rotorkin: warning: ")]
    names = [ln.rsplit(":", 1)[0] for ln in steps]
    assert names[-4:] == ["rotorkin: reading the config", "rotorkin: evaluating the design",
                          "rotorkin: writing the outputs", "rotorkin: run"]  # fmt: skip
    seconds = [float(ln.rsplit(":", 1)[1].split()[0]) for ln in steps]
    assert all(s >= 0 for s in seconds)
    assert seconds[-1] >= sum(seconds[-4:-1]) - 0.02  # "in all" holds its steps
    assert "chamber_swing_deg" in out  # stdout as without --verbose


def test_verbose_shows_the_traceback_of_an_internal_error(tmp_path, capsys, monkeypatch):
    import rotorkin.cli.run as run_module

    monkeypatch.setattr(run_module, "evaluate", lambda cfg: 1 / 0)
    code, _, err = _run(capsys, "run", "-o", str(tmp_path / "a"))
    assert code == 1 and "Traceback" not in err and "ZeroDivisionError" in err
    assert len(err.strip().splitlines()) == 1
    code, _, err = _run(capsys, "run", "-v", "-o", str(tmp_path / "b"))
    assert code == 1 and "Traceback (most recent call last)" in err


def test_a_table_on_a_pipe_is_neither_cut_nor_rounded(tmp_path):
    """stdout a pipe and COLUMNS=40: every row on one line, every value at full precision."""
    env = {**os.environ, "COLUMNS": "40", "TERM": "xterm"}
    proc = subprocess.run([sys.executable, "-m", "rotorkin.cli", "run", "-e", "guide-bar-pump",
                           "--no-figures", "-o", str(tmp_path)],
                          capture_output=True, text=True, env=env, timeout=120)  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    assert "…" not in proc.stdout
    result = evaluate(load_config(None, "guide-bar-pump", [])[0])
    lines = proc.stdout.splitlines()
    for key, meaning in result.headline.items():
        value = result.summary[key]
        row = next(ln for ln in lines if f" {key} " in ln)
        shown = repr(value) if isinstance(value, float) and math.isfinite(value) else str(value)
        assert f" {shown} " in row and meaning in row, row
    wrote = next(ln for ln in lines if ln.startswith("wrote "))
    assert "summary.json" in wrote and "no figures" in wrote


def _help(*args: str) -> str:
    from typer.testing import CliRunner

    res = CliRunner().invoke(app, [*args, "--help"], env={"COLUMNS": "200"})
    assert res.exit_code == 0, res.output
    return res.output


def test_help_lists_completion_and_every_command():
    text = _help()
    assert "--install-completion" in text and "--show-completion" in text
    for name, (_, line) in COMMANDS.items():
        assert f"  {name} " in text and line in " ".join(text.split())


@pytest.mark.parametrize("command", list(COMMANDS))
def test_each_command_has_readable_option_types_quiet_and_verbose(command):
    text = _help(command)
    options = text.split("Options:", 1)[1]
    for python_type in ("<list[", "<str>", "<int>", "<float>", "<Path>", "<path>", "<text>"):
        assert python_type not in options, (command, python_type)
    assert "-q, --quiet" in options and "-v, --verbose" in options
    if "--set" in options:
        assert "--set KEY=VALUE" in options


def test_the_command_list_is_each_commands_own_first_help_line():
    import typer

    group = typer.main.get_command(app)
    for name, (_, line) in COMMANDS.items():
        command = group.get_command(None, name)
        assert command.help.strip().splitlines()[0] == line, name


def test_help_imports_no_command():
    """``rotorkin --help`` lists the commands without importing them or numpy."""
    code = (
        "import sys, contextlib, io\n"
        "from rotorkin.cli import main\n"
        "with contextlib.redirect_stdout(io.StringIO()) as out:\n"
        "    assert main(['--help']) == 0\n"
        "assert 'optimize' in out.getvalue()\n"
        "print(sorted(m for m in sys.modules if m.startswith(('rotorkin.', 'numpy'))))"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=60)  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    loaded = ast.literal_eval(proc.stdout)
    assert "numpy" not in loaded and "rotorkin.drives" not in loaded
    assert not [m for m in loaded if m.startswith("rotorkin.cli.") and m.rsplit(".", 1)[1] in
                {mod.rsplit(".", 1)[1] for mod, _ in COMMANDS.values()}]  # fmt: skip


def test_shell_completion_of_command_names_and_options():
    """bash completion (typer's protocol): command names from the list, each once."""

    def complete(words: str) -> list[str]:
        env = {**os.environ, "_ROTORKIN_COMPLETE": "complete_bash", "COMP_WORDS": words,
               "COMP_CWORD": str(len(words.split()) - 1)}  # fmt: skip
        proc = subprocess.run([sys.executable, "-m", "rotorkin.cli"], env=env,
                              capture_output=True, text=True, timeout=60)  # fmt: skip
        assert proc.returncode == 0, proc.stderr
        return proc.stdout.split()

    assert complete("rotorkin ex") == ["examples", "export"]
    assert complete("rotorkin s") == [n for n in COMMANDS if n.startswith("s")]
    assert "--format" in complete("rotorkin run --fo")
