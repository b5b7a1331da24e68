"""The report's summary tables: human labels, a definition and a unit per row, one sign rule.

Each row of the main table is a headline key of the study (or a key the paper has a
value for): its label in words (:func:`rotorkin.report.text.key_label`, or a
curated one), what it is (the study's own one-line description, or a definition
written here where the description leaves the formula open, e.g. the torque
ripple), its value with its unit, and beside it the paper's value, the
difference, the tolerance and the source.

Torque signs: the study's ``*_torque_*`` keys are positive when the machine drives
the shaft. When the report's torque plot shows the torque the motor must supply
(a pump: ``sign = -1``), the table shows those keys on the plot's convention,
negated and named for the motor, and says so in the row; one convention per page.
"""

from __future__ import annotations

import html as _html
import re

import numpy as np

from rotorkin.report.text import esc, key_label, number, pretty, unit_scales

__all__ = ["summary_tables", "row_label", "TORQUE_SIGN_TEXT"]

#: The sign rule written next to every shaft-torque row, by the page's convention.
TORQUE_SIGN_TEXT = {
    1: "sign: positive when the machine (gas, fluid, blades) drives the shaft",
    -1: "sign: positive when the motor drives the machine (the torque it must supply)",
}

# definitions where the study's one-liner does not say how the number is computed
_DEFINITIONS = {
    "torque_ripple": "(T<sub>max</sub> − T<sub>min</sub>) / |T<sub>mean</sub>| of the shaft "
    "torque over one period, inertia not included",
    "torque_ripple_with_inertia": "(T<sub>max</sub> − T<sub>min</sub>) / |T<sub>mean</sub>| "
    "of the shaft torque with the inertia torque, over one period",
    "flow_ripple": "(Q<sub>max</sub> − Q<sub>min</sub>) / Q<sub>mean</sub> of the delivered "
    "flow over one period (time mean)",
    "flow_delivered_ripple": "(Q<sub>max</sub> − Q<sub>min</sub>) / Q<sub>mean</sub> of the "
    "flow delivered, leakage and compression loss included",
    "speed_fluctuation": "wanted coefficient of speed fluctuation (ω<sub>max</sub> − "
    "ω<sub>min</sub>) / ω<sub>mean</sub>",
    "speed_fluctuation_without_flywheel": "(ω<sub>max</sub> − ω<sub>min</sub>) / "
    "ω<sub>mean</sub> with the config's inertias alone",
}
_LABELS = {
    "mean_torque_Nm": "Mean shaft torque",
    "shaft_torque_max_Nm": "Largest shaft torque",
    "shaft_torque_min_Nm": "Smallest shaft torque",
    "shaft_torque_with_inertia_max_Nm": "Largest shaft torque with inertia",
    "shaft_torque_with_inertia_min_Nm": "Smallest shaft torque with inertia",
    "flywheel_inertia_kgm2": "Flywheel inertia needed",
    "imep_bar": "Indicated mean effective pressure (IMEP)",
    "displacement_cm3_per_rev": "Displacement per turn",
    "compression_ratio_geometric": "Compression ratio (geometric)",
    "contact_safety_factor": "Contact safety factor",
}
# the shaft-torque keys on the study's sign; on the motor's they change name (and min <-> max)
_MOTOR = {
    "mean_torque_Nm": "Mean torque the motor supplies",
    "shaft_torque_max_Nm": "Smallest torque the motor supplies",
    "shaft_torque_min_Nm": "Largest torque the motor supplies",
    "shaft_torque_with_inertia_max_Nm": "Smallest motor torque with inertia",
    "shaft_torque_with_inertia_min_Nm": "Largest motor torque with inertia",
}
_SIGNED = set(_MOTOR) | {"output_torque_mean_Nm", "shaft_output_torque_mean_Nm"}
_SIGN_NOTE_RE = re.compile(r"\s*\((?:\+|-)\s*:?[^)]*\)")
_OCR_RE = re.compile(r"\(OCR:\s*([^,()]*),\s*read\s*([^()]*)\)")


def row_label(key: str, sign: int = 1) -> tuple[str, str]:
    """``(label, unit)`` of a summary key as the table shows it (HTML)."""
    unit = key_label(key)[1]
    if sign < 0 and key in _MOTOR:
        return _MOTOR[key], unit
    return _LABELS.get(key) or key_label(key)[0], unit


def _definition(key: str, headline: dict, sign: int) -> str:
    e = _html.escape
    text = _DEFINITIONS.get(key)
    if text is None:
        text = pretty(esc(str(headline.get(key, ""))))
    if key in _SIGNED:
        text = _SIGN_NOTE_RE.sub("", text)
        text += ("; " if text else "") + TORQUE_SIGN_TEXT[sign]
        if sign < 0 and key in _MOTOR:
            text += f" (= −{e(key)} of summary.json, positive there when the machine drives)"
    return text


def _source(p: dict) -> str:
    where = _OCR_RE.sub(lambda m: f"(printed {m.group(1).strip()}, read as {m.group(2).strip()})",
                        p["where"])  # fmt: skip
    text = f"{p['reference']}, {where} ({p['kind']})"
    if p["note"]:
        text += f": {p['note']}"
    return pretty(esc(text))


def _value_html(v, unit: str, digits: int, scale: float | None) -> str:
    if isinstance(v, str):
        return _html.escape(v.replace("_", " "))
    text = number(v, digits, scale)
    if unit and not isinstance(v, (bool, np.bool_)) and text != "n/a":
        sep = "" if unit == "°" else "\u2009"
        return f"{text}{sep}<span class='unit'>{unit}</span>"
    return text


def summary_tables(result, papers: dict, sign: int = 1) -> str:
    """The main summary table (headline keys and the paper's keys) and the folded table of
    every summary key, as HTML; each table in its own horizontally scrolling box."""
    e = _html.escape
    summary, headline = result.summary, dict.fromkeys(result.headline, "")
    if isinstance(result.headline, dict):
        headline = dict(result.headline)
    scales = unit_scales(summary)
    keys = list(headline) + [k for k in papers if k not in headline]
    head = (
        "<thead><tr><th>quantity</th><th class='num'>ours</th><th class='num'>paper</th>"
        "<th class='num'>ours − paper</th><th class='num'>tolerance</th><th>source</th></tr>"
        "</thead>"
    )
    rows = []
    for key in keys:
        if key not in summary:
            continue
        label, unit = row_label(key, sign)
        ours = summary[key]
        flip = sign < 0 and key in _MOTOR and isinstance(ours, (int, float, np.number))
        if flip:
            ours = -float(ours) + 0.0
        scale = scales.get(unit)
        p = papers.get(key)
        if p is None:
            cells = "<td></td><td></td><td></td><td></td>"
            cls = ""
        else:
            ok = p["within"]
            mark = f"<span class='mark'>{'✓ within' if ok else '✗ outside'}</span>"
            cls = " class='agree'" if ok else " class='disagree'"
            big = max(abs(float(p["paper"])), abs(float(p["ours"])))
            cells = (
                f"<td class='num paper'>{_value_html(float(p['paper']), unit, 6, None)}</td>"
                f"<td class='num diff'>{_value_html(float(p['difference']), unit, 3, big)} "
                f"{mark}</td>"
                f"<td class='num tol'>±{_value_html(float(p['tolerance']), unit, 3, None)}</td>"
                f"<td class='src'>{_source(p)}</td>"
            )
        definition = _definition(key, headline, sign)
        rows.append(
            f"<tr data-key='{e(key)}'{cls}><td class='q'><span class='label'>{label}</span>"
            f"<span class='def'>{definition}</span></td>"
            f"<td class='num ours'>{_value_html(ours, unit, 6, scale)}</td>{cells}</tr>"
        )
    main = (
        "<div class='table-wrap'><table id='summary-table'>"
        f"{head}<tbody>{''.join(rows)}</tbody></table></div>"
    )
    every = []
    for key, value in summary.items():
        label, unit = row_label(key, 1)
        every.append(
            f"<tr data-key='{e(key)}'><td>{label}</td>"
            f"<td class='num'>{_value_html(value, unit, 6, scales.get(unit))}</td>"
            f"<td><code>{e(key)}</code></td></tr>"
        )
    return (
        main + f"<details class='all'><summary>All {len(summary)} summary values (as in "
        "summary.json, study sign convention)</summary><div class='table-wrap'>"
        "<table id='all-metrics'><thead><tr><th>quantity</th><th class='num'>value</th>"
        f"<th>key</th></tr></thead><tbody>{''.join(every)}</tbody></table></div></details>"
    )
