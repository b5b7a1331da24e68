"""What a drive provides: :class:`DriveSpec`, the one record every consumer reads.

A drive is one package under ``rotorkin/drives/<name>/`` whose ``spec.py`` builds a
:class:`DriveSpec`; :data:`rotorkin.drives.REGISTRY` lists them. Config
validation, ``run``, ``sweep``, ``tolerance``, ``synthesize``, ``export``,
``report``, the published-numbers table and the command-line help all iterate
the registry and call what the spec holds; none of them names a drive. Only
``name``, ``title``, ``config_model`` and ``study`` are required: a drive
without a cam simply has no CAD entries, one without a batch module is swept
design by design through its study.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from types import ModuleType

__all__ = ["DriveSpec"]


@dataclass(frozen=True)
class DriveSpec:
    """Everything rotorkin knows how to do with one drive.

    Attributes
    ----------
    name : str
        ``drive.type`` in configs, an identifier.
    title : str
        One line for people: the mechanism and the machine it drives.
    config_model : type
        The pydantic model of a whole config of this drive
        (:mod:`rotorkin.core.schema` building blocks); its defaults are the defaults.
    study : callable
        ``study(cfg) -> StudyResult`` on a validated SI config.
    headline : mapping of str -> str
        Summary keys printed by ``run``, in order, each with what it means.
    paper : str
        Short reference of the source paper ("" when none).
    published : tuple of Published
        The paper's numbers per summary key (:mod:`rotorkin.studies.published`).
    examples : tuple of str
        Built-in examples on this drive (``rotorkin run --example NAME``), each a
        file ``NAME.toml`` in ``example_dir``.
    example_dir : Path, optional
        The folder of the examples, in the drive's package (``examples/``).
    batch : module, optional
        Vectorised evaluation of many designs for ``sweep`` and ``tolerance``:
        ``KEYS``, ``CURVES``, ``ANGLE``, ``unsupported(cfg)``, ``metric_names(cfg)``,
        ``reasons(designs, code)``, ``metrics(designs, names, samples, threads)``,
        ``curves(designs, points)``, ``period(designs)``, optionally
        ``OPTIONAL_METRICS`` or ``optional_metrics(cfg)`` (metrics computed on request
        only). Without it every design goes through ``study``.
    sweep_recipes : callable, optional
        ``sweep_recipes(cfg) -> list[Recipe]``: the sweeps behind the paper's
        parameter-study figures (``rotorkin sweep --paper-figures``).
    tolerance_hold : callable, optional
        ``tolerance_hold(cfg) -> (cfg, extra)``: the config and extra values that
        keep the manufactured parts at their nominal size in a tolerance analysis.
    tolerance_first : tuple of str
        Metrics drawn first in the tolerance histograms.
    synthesize : callable, optional
        ``synthesize(cfg, raw, objective, target, harmonics, options) -> SynthesisResult``.
    objectives : mapping of str -> str
        Synthesis objectives and what each one's ``--target`` is.
    synthesis_options : tuple of str
        Options of :attr:`synthesize` beyond the common ones
        (``"max_pressure_angle"``).
    scene : module, optional
        Report builder: ``scene(result, cfg)``, ``plots(result, cfg)``,
        ``checks(result, cfg)`` (:mod:`rotorkin.render.scenes`).
    cad_parts : callable, optional
        ``cad_parts(cfg, with_parts) -> (parts, checks)``: planar parts
        (:class:`rotorkin.cams.planar.Part`) and their profile checks.
    cad_write : callable, optional
        ``cad_write(cfg, fmt, folder, name, progress=None) -> list[Path]`` for parts that
        are not planar (writes its own files; ``progress(label, done, total)`` per part
        where a format has several).
    check_cam : callable, optional
        ``check_cam(cfg)``: the cam and part checks of ``export`` without building
        anything; :func:`rotorkin.drives.evaluate` makes them before the study, so every
        command refuses what export would.
    check_rows : callable, optional
        ``check_rows(cfg) -> [(check, value)]``: the cam checks printed by ``export``;
        default: the rows of the planar profile checks.
    checks : callable, optional
        ``checks(cfg) -> [rotorkin.studies.checks.Check]``: the drive's own checks with
        their margins (raising for what it refuses outright); default: the checks of the
        planar profiles of ``cad_parts`` (:func:`rotorkin.drives.design_checks`).
    machine : str
        ``machine.type`` of the drive's own machine (its paper's), what ``study``
        evaluates; "" when the drive has none of its own.
    law : callable, optional
        ``law(cfg) -> rotorkin.vane.RotaryLaw`` for a drive that turns two coaxial
        members: it then carries any vane machine (``[machine] type``,
        :mod:`rotorkin.vane`), its own one through ``study``, the others through
        :func:`rotorkin.vane.evaluate`.
    pairs : callable, optional
        ``pairs(cfg) -> f`` with ``f(theta, drive_torque, motion) -> list[Pair]``: the
        drive's load-carrying pairs (:mod:`rotorkin.analysis.pairs`) from the torques it
        puts on its two members, for the vane machines it carries that are not its own
        (its own study reports its pairs itself).
    carries_any : bool
        ``study`` itself runs every vane machine (it adds the drive's own numbers to
        :func:`rotorkin.vane.evaluate`'s); ``headline`` then starts with the drive's
        keys and ends with those of ``machine``.
    """

    name: str
    title: str
    config_model: type
    study: Callable
    headline: Mapping[str, str] = field(default_factory=dict)
    paper: str = ""
    published: tuple = ()
    examples: tuple[str, ...] = ()
    example_dir: Path | None = None
    batch: ModuleType | None = None
    sweep_recipes: Callable | None = None
    tolerance_hold: Callable | None = None
    tolerance_first: tuple[str, ...] = ()
    synthesize: Callable | None = None
    objectives: Mapping[str, str] = field(default_factory=dict)
    synthesis_options: tuple[str, ...] = ()
    scene: ModuleType | None = None
    cad_parts: Callable | None = None
    cad_write: Callable | None = None
    check_cam: Callable | None = None
    check_rows: Callable | None = None
    checks: Callable | None = None
    machine: str = ""
    law: Callable | None = None
    pairs: Callable | None = None
    carries_any: bool = False

    def __post_init__(self):
        if not self.name.isidentifier():
            raise ValueError(f"drive name {self.name!r} is not an identifier")
