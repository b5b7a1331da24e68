"""Every command and code block of README.md and docs/ runs, and prints what the text says.

How the documents are read (the conventions they follow):

* **Fenced blocks** carry a language: ``bash``, ``python``, ``toml``, ``json`` or ``text``;
  an unlabeled fence fails. Indented code blocks may hold formulas and messages, never a
  command (a line starting with ``rotorkin `` or ``$ ``): commands are fenced.
* **bash**: one command per line (a trailing ``\\`` continues it, ``#`` after a blank
  starts a comment; ``&&`` chains commands). A ``rotorkin`` command runs through
  :func:`rotorkin.cli.main` in the working folder; it must exit with 0, or with 2 when its
  comment says it is refused. Every number in its comment must be in its output.
* **text**: a line starting with ``$ `` is a command (``\\`` continues it) and the lines
  up to the next ``$ `` are its output as shown: exit code 2 when the shown output has a
  ``rotorkin: error:`` line, else 0, and every number of the shown output must be in the
  real output. A ``rotorkin`` line without ``$`` (a synopsis) is a command too. Other
  text (layouts, tables of output) is not run.
* **Inline code** ``rotorkin <command> <arguments>`` in the prose runs too (exit 0); the
  command's name alone (``rotorkin sweep``) only names it.
* **Placeholders** are written in angle brackets: ``<CONFIG.toml>``, ``<DIR>``,
  ``<KEY>=<VALUE>``, ``<NAME>``. A command holding one is not run: every such command is
  listed in :data:`PLACEHOLDERS` and the test fails when the documents' set differs from
  that list. Setup commands (``pip install ...``) and the test suite itself
  (``python -m pytest``), :data:`SETUP`, are not run either. Nothing else is left out.
* **Benchmarks** (``python benchmarks/<script>.py ...``) take minutes on a quiet machine:
  their arguments are parsed by the script's own parser, which must accept them (exit 0),
  and the script stops there; the numbers in their comments are timings, not compared.
* **python**: each block is executed (``exec``) on its own in the working folder; a line
  ``expression  # comment`` whose comment holds numbers or a quoted string must show
  them in the expression's ``repr``.
* **toml**: validated by :func:`rotorkin.io.config.load_config`; a fragment without
  ``[drive]`` is merged into the default example first. ``<!-- file: NAME -->`` before the
  block writes it to ``NAME`` in the working folder before the document's commands run
  (``rotorkin run my-engine.toml`` runs the README's config).
* **json**: ``<!-- summary-of: COMMAND -->`` before the block: its keys and values must be
  in the ``summary.json`` that ``COMMAND`` (a ``rotorkin run``) writes.
* ``<!-- summary-table: NAME = COMMAND; ... -->`` before a table: in each row, the cell of
  column ``NAME`` must show the values of the row's ``keys`` (``a_min_cm3``, ``_max_cm3``
  is ``a_min_cm3, a_max_cm3``) in the summary.json of ``COMMAND``: one value for each key
  (comma-separated) or one for all; numbers at their precision, units after them
  allowed, ``true``/``false``, text as written.
* ``<!-- expect: 38.94, 16 -->`` right after a block: each number must be in the paragraph
  after the marker and in the output of the block's commands.
* **Numbers** match when the output has one that rounds to the written one at its
  decimals (``35.489`` matches ``35.4889899177``; ``62 271`` is 62271); magnitudes below
  1e-9 are round-off and match any round-off; a number of seconds (``0.13 s``, a
  timing) is not compared.

Files a reader brings: ``motion.csv`` (a table of rotor angles) is the ``tabulated``
example's table. All documents share one temporary working folder, in the order of
:data:`DOCS`, their commands in the order written (a later command may read what an
earlier one wrote); a command that appears twice runs once.
"""

from __future__ import annotations

import contextlib
import io
import json
import math
import os
import re
import shlex
import shutil
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

DOCS = [
    p.relative_to(ROOT).as_posix()
    for p in [
        ROOT / "README.md",
        *sorted((ROOT / "docs").glob("*.md")),
        *sorted((ROOT / "docs").glob("*/*.md")),
    ]  # fmt: skip
]

#: Commands with placeholders, not run (the documents' set must equal this one).
PLACEHOLDERS = frozenset({
    # README.md: a sweep on dask (the keys to vary are the reader's)
    "rotorkin sweep -e wobble-cam-engine --vary <KEY>=<RANGE> --workers 2",
    # docs/cams.md
    "rotorkin export <CONFIG> --format stl|step|csv|dxf --out <DIR>",
    "rotorkin export [<CONFIG>] [--example <NAME>] [--set <KEY>=<VALUE> ...] "
    "--format dxf|stl|step|csv|all [--out <DIR>] [--quiet]",
    # docs/conventions.md
    "rotorkin keys [<DRIVE_TYPE>]",
    # docs/design.md
    "rotorkin solve [<CONFIG> | -e <NAME>] [--set <KEY>=<VALUE> ...] --for <KEY> "
    "--target <METRIC>=<VALUE> [--within <LO>:<HI>] [--scan <N>] [--out <DIR>]",
    "rotorkin run <DIR>/config.toml",
    "rotorkin optimize [<CONFIG> | -e <NAME>] [--set <KEY>=<VALUE> ...] --vary <KEY>=<LO>:<HI> "
    "... --objective max:<METRIC> --objective min:<METRIC> ... [--constraint "
    "<METRIC><=<VALUE> ...] [--population <N>] [--generations <G>] [--seed <S>] --out <DIR> "
    "[--resume] [--report <INDEX>]",
    # docs/report.md
    "rotorkin report [<CONFIG>] [--example <NAME>] [--set <KEY>=<VALUE> ...] [--out <DIR>] "
    "[--strict]",
    "rotorkin run [<CONFIG>] [--example <NAME>] [--set <KEY>=<VALUE> ...] [--out <DIR>] --report",
    # docs/sweeps.md
    "rotorkin sweep <CONFIG.toml> --vary drive.lambda=0.2:0.8:61 --vary drive.driver=crank,guide "
    "--curves --workers 2 --out results/pump",
    "rotorkin run --set <KEY>=<VALUE>",
    # docs/synthesis.md
    "rotorkin synthesize [<CONFIG>] [--example <NAME>] [--set <KEY>=<VALUE> ...] --objective "
    "<NAME> [--target <VALUE>] [--harmonics <N>] [--max-pressure-angle <ANGLE>] [--out <DIR>] "
    "[--quiet]",
    "rotorkin run <DIR>/synthesized.toml",
})  # fmt: skip

#: Setup commands (``pip install ...``) and the test suite itself, not run.
SETUP = ("pip install ", "python -m pytest")
#: Benchmark commands: their arguments parsed by the script, which stops there.
BENCHMARK = "python benchmarks/"
#: Runs a benchmark script with ``parse_args`` ending the run once the arguments are read.
PARSE_ONLY = """
import argparse, runpy, sys
parse = argparse.ArgumentParser.parse_args
def parse_only(self, args=None, namespace=None):
    parse(self, args, namespace)
    print("arguments accepted")
    raise SystemExit(0)
argparse.ArgumentParser.parse_args = parse_only
sys.argv = sys.argv[1:]
runpy.run_path(sys.argv[0], run_name="__main__")
"""

LANGUAGES = ("bash", "python", "toml", "json", "text")
NUMBER = re.compile(r"(?<![\w.])[-+]?\d+(?:[ \u202f]\d{3})*(?:\.\d+)?(?:[eE][-+]?\d+)?(?![\w.]*\w)")
SECONDS = re.compile(r"\s*s\b")
PLACEHOLDER = re.compile(r"<[^<>\s]+>")


# --- reading the documents ------------------------------------------------------------------
@dataclass
class Command:
    doc: str
    line: int
    text: str  # as written, continuation joined
    expect_rc: int = 0
    numbers: list = field(default_factory=list)  # written in the comment or shown output
    context: str = ""  # where the numbers come from


@dataclass
class Table:
    doc: str
    line: int
    columns: dict  # column name -> the command whose summary.json it shows
    rows: list  # cells of each row under the header


@dataclass
class Block:
    doc: str
    line: int
    lang: str
    body: list
    markers: dict = field(default_factory=dict)
    expect: list = field(default_factory=list)
    after: str = ""  # the paragraph after an expect marker


MARKER = re.compile(r"^<!--\s*([\w-]+):\s*(.*?)\s*-->\s*$")


def read_doc(doc: str):
    """Split a document into fenced blocks, inline commands, problems found, summary tables."""
    lines = (ROOT / doc).read_text(encoding="utf-8").split("\n")
    blocks, inline, problems, tables = [], [], [], []
    pending: dict = {}
    prose: list[tuple[int, str]] = []
    i = 0
    while i < len(lines):
        line = lines[i]
        fence = re.match(r"^\s*```(\S*)\s*$", line)
        marker = MARKER.match(line.strip())
        if fence:
            start, lang, body = i + 1, fence.group(1), []
            i += 1
            while i < len(lines) and not re.match(r"^\s*```\s*$", lines[i]):
                body.append(lines[i])
                i += 1
            if lang not in LANGUAGES:
                problems.append(f"{doc}:{start}: fence without a language of {LANGUAGES}")
            blocks.append(Block(doc, start, lang, body, pending))
            pending = {}
        elif marker and marker.group(1) == "expect":
            if not blocks:
                problems.append(f"{doc}:{i + 1}: expect marker before any block")
            else:
                blocks[-1].expect = [s for s in re.split(r"[,\s]+", marker.group(2)) if s]
                para, j = [], i + 1
                while j < len(lines) and not lines[j].strip():
                    j += 1
                while j < len(lines) and lines[j].strip():
                    para.append(lines[j])
                    j += 1
                blocks[-1].after = " ".join(para)
        elif marker and marker.group(1) == "summary-table":
            columns = dict(
                (s.strip() for s in part.split("=", 1)) for part in marker.group(2).split(";")
            )
            j = i + 1
            while j < len(lines) and not lines[j].strip():
                j += 1
            rows = []
            while j < len(lines) and lines[j].lstrip().startswith("|"):
                cells = re.split(r"(?<!\\)\|", lines[j].strip().strip("|"))
                rows.append([c.strip().replace("\\|", "|") for c in cells])
                j += 1
            if len(rows) < 3:
                problems.append(f"{doc}:{i + 1}: summary-table marker without a table after it")
            tables.append(Table(doc, i + 1, columns, rows))
        elif marker:
            pending[marker.group(1)] = marker.group(2)
        else:
            if re.match(r"^ {4,}(\$ |rotorkin )", line):
                problems.append(f"{doc}:{i + 1}: a command in an indented block: fence it")
            prose.append((i + 1, line))
        i += 1
    # inline spans, paragraph by paragraph (a span may wrap)
    para, first = [], None
    for number, text in [*prose, (None, "")]:
        if text.strip():
            first = first or number
            para.append(text)
            continue
        joined = " ".join(para)
        for span in re.findall(r"`(rotorkin [^`]+)`", joined):
            if len(shlex.split(span)) > 2:
                inline.append(Command(doc, first, span))
        para, first = [], None
    return blocks, inline, problems, tables


def _logical_lines(body):
    """``(first line index, line)`` with the lines continued by a trailing ``\\`` joined."""
    out, current, start = [], "", None
    for k, raw in enumerate(body):
        line = raw.rstrip()
        if start is None:
            start = k
        if line.endswith("\\"):
            current += line[:-1].rstrip() + " "
            continue
        out.append((start, current + line.strip() if current else line))
        current, start = "", None
    if current:
        out.append((start, current))
    return out


def _split_comment(line: str) -> tuple[str, str]:
    """``command  # comment`` -> (command, comment); a ``#`` inside quotes is kept."""
    quote = None
    for k, ch in enumerate(line):
        if quote:
            quote = None if ch == quote else quote
        elif ch in "\"'":
            quote = ch
        elif ch == "#" and (k == 0 or line[k - 1].isspace()):
            return line[:k].strip(), line[k + 1 :].strip()
    return line.strip(), ""


def commands_of(block: Block) -> list[Command]:
    """The commands of a bash or text block, with what each must print."""
    out = []
    if block.lang == "bash":
        for k, line in _logical_lines(block.body):
            text, comment = _split_comment(line)
            if not text and out:  # a comment line goes on with the command above
                out[-1].context += " " + comment
                out[-1].numbers += numbers_in(comment)
                out[-1].expect_rc = 2 if "refused" in out[-1].context.lower() else 0
                continue
            for part in (p.strip() for p in text.split("&&")):
                refused = "refused" in comment.lower()
                out.append(Command(block.doc, block.line + k, part, 2 if refused else 0,
                                   numbers_in(comment), comment))  # fmt: skip
    elif block.lang == "text":
        shown: list[str] = []
        lines = block.body
        k = 0
        while k < len(lines):
            line = lines[k]
            if line.startswith("$ ") or line.startswith("rotorkin "):
                text = line[2:] if line.startswith("$ ") else line
                start = k
                while text.rstrip().endswith("\\") and k + 1 < len(lines):
                    k += 1
                    text = text.rstrip()[:-1].rstrip() + " " + lines[k].strip()
                shown = []
                out.append(Command(block.doc, block.line + start, text.strip()))
                if not line.startswith("$ "):  # a synopsis: nothing shown
                    out[-1].context = "synopsis"
            elif out and out[-1].context != "synopsis":
                shown.append(line)
                out[-1].numbers = numbers_in("\n".join(shown))
                out[-1].expect_rc = 2 if any(s.startswith("rotorkin: error:") for s in shown) else 0
                out[-1].context = "\n".join(shown)
            k += 1
    for cmd in out:
        cmd.numbers += list(block.expect)
    return out


def numbers_in(text: str) -> list[str]:
    """The numbers written in ``text``, leaving out seconds (timings)."""
    found = []
    for m in NUMBER.finditer(text):
        if SECONDS.match(text, m.end()):
            continue
        found.append(m.group(0))
    return found


def _value(s: str) -> float:
    return float(s.replace(" ", "").replace("\u202f", ""))


def _decimals(s: str) -> int:
    s = s.replace(" ", "").replace("\u202f", "")
    mantissa = re.split(r"[eE]", s)[0]
    return len(mantissa.split(".")[1]) if "." in mantissa else 0


def number_shown(written: str, output: str) -> bool:
    """Whether ``output`` has a number that reads as ``written`` at its precision."""
    x = _value(written)
    values = [_value(n) for n in NUMBER.findall(output)]
    if abs(x) < 1e-9:
        return any(abs(v) < 1e-9 for v in values)
    if re.search(r"[eE]", written):
        digits = len(re.split(r"[eE]", written)[0].lstrip("+-").replace(".", "").lstrip("0"))
        half = 0.5 * 10 ** (math.floor(math.log10(abs(x))) - digits + 1)
    else:
        half = 0.5 * 10 ** -_decimals(written)
    return any(abs(v - x) <= half * (1 + 1e-9) for v in values)


def placeholder(text: str) -> bool:
    return bool(PLACEHOLDER.search(text))


def _all_commands(doc: str):
    blocks, inline, _, _ = read_doc(doc)
    cmds = [c for b in blocks for c in commands_of(b)] + inline
    return sorted(cmds, key=lambda c: c.line)


# --- running them ---------------------------------------------------------------------------
class Runner:
    """Runs the documents' commands in one working folder; each distinct command once."""

    def __init__(self, work: Path):
        self.work = work
        self.done: dict[str, tuple[int, str]] = {}
        self.summaries: dict[str, dict] = {}  # summary.json as each command wrote it

    @contextlib.contextmanager
    def _here(self):
        old, env = Path.cwd(), os.environ.get("COLUMNS")
        os.chdir(self.work)
        os.environ["COLUMNS"] = "200"  # rich: one line per table row
        try:
            yield
        finally:
            os.chdir(old)
            if env is None:
                os.environ.pop("COLUMNS", None)
            else:
                os.environ["COLUMNS"] = env

    def run(self, text: str) -> tuple[int, str]:
        if text in self.done:
            return self.done[text]
        if text.startswith(BENCHMARK):
            self.done[text] = self.parse_benchmark(text)
            return self.done[text]
        argv = shlex.split(text)
        assert argv[0] == "rotorkin", f"no way to run {text!r}"
        from rotorkin.cli import main

        with self._here():
            out, err = io.StringIO(), io.StringIO()
            with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
                rc = main(argv[1:])
            result = (rc, out.getvalue() + err.getvalue())
            folder = re.search(r"wrote (\S+?)/?:", result[1])
            if folder and (self.work / folder.group(1) / "summary.json").is_file():
                summary = (self.work / folder.group(1) / "summary.json").read_text()
                self.summaries[text] = json.loads(summary)
        self.done[text] = result
        return result

    def parse_benchmark(self, text: str) -> tuple[int, str]:
        """A benchmark's arguments read by its own parser (the benchmark does not run)."""
        import subprocess
        import sys

        argv = shlex.split(text)
        proc = subprocess.run([sys.executable, "-c", PARSE_ONLY, *argv[1:]], cwd=ROOT,
                              capture_output=True, text=True, timeout=120)  # fmt: skip
        return proc.returncode, proc.stdout + proc.stderr

    def exec_python(self, source: str) -> dict[int, str]:
        """Execute a python block; the repr of each expression statement by its line."""
        import ast

        tree = ast.parse(source)
        scope: dict = {"__name__": "__doc_block__"}
        shown = {}
        with self._here():
            for node in tree.body:
                if isinstance(node, ast.Expr):
                    value = eval(compile(ast.Expression(node.value), "<doc>", "eval"), scope)
                    shown[node.lineno] = repr(value)
                else:
                    exec(compile(ast.Module([node], []), "<doc>", "exec"), scope)
        import matplotlib.pyplot as plt

        plt.close("all")
        return shown


@pytest.fixture(scope="module")
def runner(tmp_path_factory):
    work = tmp_path_factory.mktemp("docs")
    table = ROOT / "src/rotorkin/drives/tabulated/examples"
    csvs = sorted(table.glob("*.csv"))
    assert csvs, "the tabulated example's table is missing"
    shutil.copyfile(csvs[0], work / "motion.csv")
    return Runner(work)


def _check_command(runner: Runner, cmd: Command, errors: list) -> str | None:
    where = f"{cmd.doc}:{cmd.line}: {cmd.text}"
    rc, out = runner.run(cmd.text)
    if rc != cmd.expect_rc:
        errors.append(f"{where}\n  exit code {rc}, not {cmd.expect_rc}\n{out[-2000:]}")
        return out
    missing = [n for n in cmd.numbers if not number_shown(n, out)]
    if missing:
        errors.append(f"{where}\n  numbers not in the output: {missing}\n{out[-4000:]}")
    return out


def _check_toml(runner: Runner, block: Block, errors: list) -> None:
    from rotorkin.io.config import load_config, validate_config

    text = "\n".join(block.body)
    try:
        data = tomllib.loads(text)
        if "drive" in data:  # a config, read from a file as the reader would
            path = runner.work / block.markers.get("file", f"block_{block.line}.toml")
            path.write_text(text)
            load_config(path)
        else:  # a fragment: the default example with these keys
            _, raw, _ = load_config()
            merged = {**raw, **{s: {**raw.get(s, {}), **keys} for s, keys in data.items()}}
            validate_config(merged)
    except Exception as exc:  # noqa: BLE001 - every failure is the document's
        errors.append(f"{block.doc}:{block.line}: the toml block does not validate: {exc}")


def _check_json(runner: Runner, block: Block, errors: list) -> None:
    where = f"{block.doc}:{block.line}"
    data = json.loads("\n".join(block.body))
    source = block.markers.get("summary-of")
    if source is None:
        errors.append(f"{where}: a json block without <!-- summary-of: COMMAND -->")
        return
    summary = _summary_of(runner, source, errors, where)
    for key, value in data.items() if summary is not None else ():
        written = value if isinstance(value, str) else json.dumps(value)
        if key not in summary or not _same(written, summary[key]):
            errors.append(f"{where}: {key} = {summary.get(key)!r} ({source}), not {value!r}")


def _summary_of(runner: Runner, command: str, errors: list, where: str) -> dict | None:
    """The summary.json that ``command`` (a ``rotorkin run``) wrote."""
    rc, out = runner.run(command)
    if rc != 0 or command not in runner.summaries:
        errors.append(f"{where}: {command} wrote no summary:\n{out[-2000:]}")
        return None
    return runner.summaries[command]


def _same(cell: str, value) -> bool:
    """Whether a table cell or json value as written shows the summary's ``value``."""
    cell = cell.strip().strip("`")
    if isinstance(value, bool) or cell in ("true", "false"):
        return str(value).lower() == cell
    lead = NUMBER.match(cell)
    if isinstance(value, (int, float)) and lead:  # a number, perhaps with its unit
        return number_shown(lead.group(0), json.dumps(value))
    return str(value) == cell


def _keys(cell: str) -> list[str]:
    """The summary keys of a row: ``a_min_cm3``, ``_max_cm3`` is ``a_min_cm3, a_max_cm3``."""
    keys: list[str] = []
    for name in re.findall(r"`([^`]+)`", cell):
        if name.startswith("_") and keys:
            base = keys[-1].split("_")
            name = "_".join(base[: len(base) - name.count("_")]) + name
        keys.append(name)
    return keys


def _check_table(runner: Runner, table: Table, errors: list) -> None:
    header, *rows = table.rows
    rows = [r for r in rows if not set("".join(r)) <= set("-: ")]  # the separator row
    where = f"{table.doc}:{table.line}"
    for name, command in table.columns.items():
        if name not in header:
            errors.append(f"{where}: no column {name!r} in the table")
            continue
        summary = _summary_of(runner, command, errors, where)
        if summary is None:
            continue
        col = header.index(name)
        for row in rows:
            keys, values = _keys(row[0]), [v.strip() for v in row[col].split(", ")]
            if len(values) == 1:  # one value for every key of the row
                values = values * len(keys)
            if not keys or len(values) != len(keys):
                errors.append(f"{where}: row {row[0]!r}: {len(keys)} keys, {row[col]!r}")
                continue
            for key, cell in zip(keys, values, strict=True):
                if key not in summary:
                    errors.append(f"{where}: {key} is not a summary key of {command}")
                elif not _same(cell, summary[key]):
                    errors.append(f"{where}: {key} = {summary[key]!r} ({command}), "
                                  f"the table says {cell!r}")  # fmt: skip


def _check_python(runner: Runner, block: Block, errors: list) -> None:
    source = "\n".join(block.body)
    try:
        shown = runner.exec_python(source)
    except Exception as exc:  # noqa: BLE001 - every failure is the document's
        errors.append(f"{block.doc}:{block.line}: the python block fails: {exc!r}")
        return
    for k, line in enumerate(block.body, start=1):
        _, comment = _split_comment(line)
        wanted = re.findall(r'"([^"]+)"', comment) + numbers_in(re.sub(r'"[^"]*"', "", comment))
        if not wanted or k not in shown:
            continue
        for item in wanted:
            ok = item in shown[k] if not NUMBER.fullmatch(item) else number_shown(item, shown[k])
            if not ok:
                errors.append(f"{block.doc}:{block.line + k}: {item!r} not in {shown[k][:300]}")


@pytest.mark.slow
@pytest.mark.parametrize("doc", DOCS)
def test_every_block_runs_as_documented(doc, runner):
    blocks, inline, _, tables = read_doc(doc)
    errors: list[str] = []
    for block in blocks:  # the reader's files first
        if block.lang == "toml" and "file" in block.markers:
            (runner.work / block.markers["file"]).write_text("\n".join(block.body))
    items = [(b.line, b) for b in blocks] + [(c.line, c) for c in inline]
    items += [(tb.line, tb) for tb in tables]
    for _, item in sorted(items, key=lambda it: it[0]):
        if isinstance(item, Table):
            _check_table(runner, item, errors)
            continue
        if isinstance(item, Command):
            if not placeholder(item.text):
                _check_command(runner, item, errors)
            continue
        block = item
        if block.lang in ("bash", "text"):
            outputs = []
            for cmd in commands_of(block):
                if placeholder(cmd.text) or cmd.text.startswith(SETUP):
                    continue
                if cmd.text.startswith(BENCHMARK):
                    cmd.numbers = []  # timings
                outputs.append(_check_command(runner, cmd, errors) or "")
            for n in block.expect:
                if n not in block.after:
                    errors.append(f"{doc}:{block.line}: expected {n} is not in the text after it")
        elif block.lang == "python":
            _check_python(runner, block, errors)
        elif block.lang == "toml":
            _check_toml(runner, block, errors)
        elif block.lang == "json":
            _check_json(runner, block, errors)
    assert not errors, "\n\n".join(errors)


# --- what is not run, and the rules of the documents ----------------------------------------
def test_documents_follow_the_conventions():
    problems = [p for doc in DOCS for p in read_doc(doc)[2]]
    assert not problems, "\n".join(problems)


def test_placeholders_are_the_listed_ones_and_every_other_command_runs():
    found, strangers = set(), []
    for doc in DOCS:
        for cmd in _all_commands(doc):
            if placeholder(cmd.text):
                found.add(cmd.text)
            elif not cmd.text.startswith(("rotorkin ", BENCHMARK, *SETUP)):
                strangers.append(f"{cmd.doc}:{cmd.line}: {cmd.text}")
    assert found == PLACEHOLDERS, (
        f"not listed: {sorted(found - PLACEHOLDERS)}; gone: {sorted(PLACEHOLDERS - found)}"
    )
    assert not strangers, "no way to run:\n" + "\n".join(strangers)


def test_no_word_of_the_workflow_in_the_documents():
    words = re.compile(r"\b(issues?|reviews?|reviewed|briefs?|tickets?)\b", re.I)
    hits = []
    for path in [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*"))]:
        if path.suffix in (".md", ".rst", ".py") and path.is_file():
            for k, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1):
                if words.search(line):
                    hits.append(f"{path.relative_to(ROOT)}:{k}: {line.strip()}")
    assert not hits, "\n".join(hits)


def test_numbers_are_read_at_their_precision():
    assert number_shown("35.489", "casing_radius = 35.4889899177 mm")
    assert not number_shown("35.48", "casing_radius = 35.4889899177 mm gives 20")
    assert number_shown("62 271", "piston_force_peak_N  62270.54")
    assert number_shown("1.30834e+14", "covers 1 ... 1.30834e+14")
    assert not number_shown("1.30835e+14", "covers 1 ... 1.30834e+14")
    assert number_shown("-4.97e-14", "residual 3.1e-15")
    assert numbers_in("303 designs in 0.13 s, 16 strokes") == ["303", "16"]
    assert numbers_in("rotor1, H8/f7, p99, 8.0315 (8 + 0.0315)") == ["8.0315", "8", "0.0315"]


def test_a_benchmark_command_is_checked_by_its_own_parser(tmp_path):
    runner = Runner(tmp_path)
    rc, out = runner.parse_benchmark("python benchmarks/bench_kinematics.py --sizes 1e5")
    assert (rc, out.strip()) == (0, "arguments accepted")
    rc, out = runner.parse_benchmark("python benchmarks/bench_kinematics.py --no-such-option 3")
    assert rc == 2 and "--no-such-option" in out


def test_the_benchmark_tables_are_those_of_the_result_files():
    """Each ``<!-- bench:TAG -->`` table of docs/performance.md is what benchmarks/run.py
    writes from benchmarks/results/ (the figures come from the measurements, not by hand)."""
    import subprocess
    import sys

    code = "import json, sys; sys.path.insert(0, 'benchmarks'); import run; " \
           "print(json.dumps(run.tables()))"  # fmt: skip
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True,
                         text=True, check=True, timeout=120).stdout  # fmt: skip
    tables = json.loads(out.strip().splitlines()[-1])
    text = (ROOT / "docs/performance.md").read_text(encoding="utf-8")
    tags = re.findall(r"<!-- bench:([\w-]+) -->", text)
    assert sorted(tags) == sorted(tables), "markers and the tables run.py writes differ"
    for tag, body in tables.items():
        start, end = f"<!-- bench:{tag} -->\n", f"\n<!-- /bench:{tag} -->"
        shown = text[text.index(start) + len(start) : text.index(end)]
        assert shown == body.rstrip(), f"the {tag} table is not that of the result file"
