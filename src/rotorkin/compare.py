"""One vane machine on several drives, sized to the same displacement: which drive to use?

:func:`compare` takes a config (its machine, loads and run, and its drive as the
first candidate) and more drives, each by name (its built-in example's
``[drive]`` section, the drive's default design) or with a ``[drive]`` section of
its own. On every drive the machine runs through :func:`rotorkin.vane.evaluate`
(the same physics as each drive's own study), with its axial width (its section
diameter for a circular torus) scaled so that the displacement per shaft turn
equals the first drive's. A drive the machine does not fit is reported with its
one-line reason and left out.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from rotorkin import drives
from rotorkin.core.errors import ConfigError, RotorkinError
from rotorkin.io.config import load_config, validate_config
from rotorkin.render.figures import degree_axis, pyplot, save
from rotorkin.vane import evaluate as evaluate_machine

__all__ = ["Comparison", "compare", "ROWS", "plot_comparison"]

#: The rows of the comparison: summary key -> what it is.
ROWS = {
    "displacement_cm3_per_rev": "displacement per shaft turn [cm^3]",
    "sized_width_mm": "axial width (section diameter) giving that displacement [mm]",
    "relative_swing_deg": "swing of the members against each other [deg]",
    "volume_cycles_per_rev": "volume cycles of a chamber per turn",
    "member_accel_peak_per_rad": "peak member acceleration / shaft speed^2",
    "member_jerk_peak_per_rad2": "peak member jerk / shaft speed^3",
    "member1_accel_peak_rad_per_s2": "peak member 1 acceleration at the run speed [rad/s^2]",
    "tdc_dwell_deg": "dwell within 1 % of the stroke of a dead centre [deg]",
    "compression_ratio_geometric": "V_max / V_min of a chamber",
    "mean_torque_Nm": "mean torque on the shaft [N m]",
    "torque_ripple": "(max - min) / |mean| of the shaft torque",
    "flywheel_inertia_kgm2": "flywheel for the speed fluctuation [kg m^2]",
    "indicated_power_kW": "power at the run speed [kW]",
}


@dataclass
class Comparison:
    """The machine on each drive that carries it; the drives that refused, with why."""

    machine: str
    results: dict = field(default_factory=dict)  # label -> StudyResult
    configs: dict = field(default_factory=dict)  # label -> validated config
    refused: dict = field(default_factory=dict)  # label -> one-line reason

    def table(self) -> dict:
        """Row key -> {label: value}, for the keys of :data:`ROWS`."""
        return {k: {n: r.summary.get(k, float("nan")) for n, r in self.results.items()}
                for k in ROWS}  # fmt: skip


#: Sections of a config that belong to the machine and the run, not to the drive.
_MACHINE_SECTIONS = ("title", "machine", "loads", "run", "export")


def _own(raw: dict) -> dict:
    """The sections of a config that belong to its drive: ``[drive]``, a cam, ..."""
    return {k: v for k, v in raw.items() if k not in _MACHINE_SECTIONS}


def _drive_section(item, base_raw: dict):
    """(label, the drive's sections) of one candidate: a name, ``name=CONFIG`` or a mapping."""
    if isinstance(item, dict):
        return item.get("type", "drive"), {"drive": dict(item)}
    text = str(item)
    name, _, path = text.partition("=")
    if path:
        _, raw, _ = load_config(path)
        if raw["drive"].get("type") != name:
            raise ConfigError(f"--drive {text!r} is not admissible: {path} holds drive.type = "
                              f"{raw['drive'].get('type')!r}, not {name!r}")  # fmt: skip
        return f"{name} ({Path(path).stem})", _own(raw)
    spec = drives.get(name)
    if name == base_raw["drive"]["type"]:
        return name, _own(base_raw)
    if not spec.examples:
        raise ConfigError(f"--drive {name!r} is not admissible: it ships no example to take "
                          f"its design from; give one as {name}=CONFIG")  # fmt: skip
    _, raw, _ = load_config(example=spec.examples[0])
    return name, _own(raw)


def _width_key(cfg: dict) -> str:
    machine = cfg["machine"]
    if machine["type"] == "twin_rotor" and machine.get("section") == "circular":
        return "section_diameter"
    return "axial_width"


def _run(base_raw: dict, sections: dict, kind: str, width: float | None):
    raw = {k: copy.deepcopy(v) for k, v in base_raw.items() if k in _MACHINE_SECTIONS}
    raw.update(copy.deepcopy(sections))
    raw.setdefault("machine", {})["type"] = kind
    cfg = validate_config(raw)
    key = _width_key(cfg)
    if width is not None:
        cfg["machine"][key] = width
    spec = drives.get(cfg["drive"]["type"])
    if spec.law is None:
        raise ConfigError(f"drive.type = {spec.name} does not turn two coaxial members: it "
                          "carries no vane machine")  # fmt: skip
    if spec.check_cam is not None:
        spec.check_cam(cfg)
    result = evaluate_machine(cfg, spec.law(cfg), drive_type=spec.name,
                              title=f"{kind.replace('_', ' ')} on {spec.name}")  # fmt: skip
    return cfg, result


def compare(base_raw: dict, candidates) -> Comparison:
    """Run the machine of ``base_raw`` on its own drive and on every candidate drive.

    Parameters
    ----------
    base_raw : dict
        A config as written (:func:`rotorkin.io.config.load_config`'s ``raw``, paths
        absolute); its ``[machine]`` (``type``: default its drive's own machine),
        ``[loads]`` and ``[run]`` are used on every drive.
    candidates : sequence
        Drive names (``"noncircular_gears"``: the drive's example design),
        ``"name=CONFIG"`` (the ``[drive]`` of that file) or ``[drive]`` mappings.

    Returns
    -------
    Comparison
        The first drive is the base config's; widths are scaled to its displacement.
    """
    base_cfg = validate_config(base_raw)
    kind = drives.machine_type(base_cfg)
    if drives.get(base_cfg["drive"]["type"]).law is None:
        raise ConfigError(f"drive.type = {base_cfg['drive']['type']} carries no vane machine: "
                          "compare needs a config of a vane machine")  # fmt: skip
    out = Comparison(machine=kind)
    items = [base_raw["drive"]["type"], *candidates]
    target = None
    for item in items:
        label, section = _drive_section(item, base_raw)
        while label in out.results or label in out.refused:
            label += "'"
        try:
            cfg, result = _run(base_raw, section, kind, None)
            disp = result.summary["displacement_cm3_per_rev"]
            key = _width_key(cfg)
            if target is None:
                target = disp
            else:
                power = 0.5 if key == "section_diameter" else 1.0
                width = cfg["machine"][key] * (target / disp) ** power
                cfg, result = _run(base_raw, section, kind, width)
        except RotorkinError as exc:
            if target is None:
                raise
            out.refused[label] = str(exc)
            continue
        result.summary["sized_width_mm"] = cfg["machine"][_width_key(cfg)] * 1e3
        out.results[label] = result
        out.configs[label] = cfg
    return out


def plot_comparison(comparison: Comparison, outdir: Path) -> list[Path]:
    """``compare.png``: chamber volume, member speed ratios and shaft torque per drive."""
    plt = pyplot()
    fig, axes = plt.subplots(3, 1, figsize=(8.0, 9.0), sharex=True)
    for i, (label, r) in enumerate(comparison.results.items()):
        c = r.columns
        theta = np.asarray(c["theta_deg"])
        keep = theta <= 360.0 + 1e-9
        style = {"color": f"C{i}", "lw": max(3.0 - 0.7 * i, 1.0)}  # coinciding curves show
        axes[0].plot(theta[keep], c["chamber_a_volume_cm3"][keep], label=label, **style)
        axes[1].plot(theta[keep], c["member1_speed_ratio"][keep], label=label, **style)
        axes[1].plot(theta[keep], c["member2_speed_ratio"][keep], ls="--", **style)
        axes[2].plot(theta[keep], c["shaft_torque_Nm"][keep], label=label, **style)
    axes[0].set_ylabel("chamber 1 volume [cm^3]")
    axes[1].set_ylabel("member speed / shaft speed\n(member 1 solid, 2 dashed)")
    axes[2].set_ylabel("shaft torque [N m]")
    for ax in axes[:2]:
        ax.grid(True, alpha=0.4)
    axes[0].legend(loc="best", fontsize=8)
    degree_axis(axes[2], 360.0, 45.0, "shaft angle theta [deg]")
    fig.suptitle(f"{comparison.machine.replace('_', ' ')} on {len(comparison.results)} drives, "
                 "same displacement", fontsize=10)  # fmt: skip
    return [save(fig, Path(outdir) / "compare.png")]
