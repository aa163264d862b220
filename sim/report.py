"""Batch grasp validation reports: ``index.html`` with plots and images, and its JSON and CSV twins.

:func:`write_report` takes result rows (``grasp_validations`` rows as dicts, optionally with the object's
``shape`` and ``material``; ``details`` as a dict or JSON text) and writes into ``out_dir``:

- ``index.html``: success rates by hand program, grasp type, shape and material (tables and matplotlib
  plots saved as PNG files beside it), per object its first choice and, where it differs, its validated
  choice (sim/choice.py) with their renders (``images/``, written by the worker), or why no candidate
  holds (:func:`failure_cause`), and a table of every trial with outcome, slip, rotation and forces;
- ``results.json`` (summary, rates and rows) and ``results.csv`` (one row per trial).

Object names and reasons come from scraped pages: every piece of text goes through :func:`html.escape`
before it reaches the page (the template is filled only with escaped fragments), and image links are
file names made by the worker, checked to be plain names inside ``images/``.
"""

from __future__ import annotations

import csv
import datetime as _dt
import html
import json
import math
import re
from collections.abc import Callable, Iterable, Mapping
from importlib import resources
from pathlib import Path
from string import Template
from typing import Any

from kb.csvio import spreadsheet_cell
from kb.jsonable import to_jsonable
from sim.diagnosis import failure_cause, is_setup_failure
from sim.protocols import DEFAULT_PROTOCOL
from sim.task import row_details

__all__ = ["CSV_FIELDS", "success_rates", "write_report"]

#: Columns of results.csv, in order.
CSV_FIELDS = (
    "object_name", "shape", "material", "rank", "grasp_type", "family", "seed", "outcome", "success",
    "reason", "slip_cm", "rotation_deg", "grip_force_n", "max_contact_force_n", "simulator", "hand_version",
    "planner_version", "features_hash", "image", "program", "protocol",
)  # fmt: skip
_GROUPS = (
    ("program", "hand program"), ("grasp_type", "grasp type"), ("shape", "shape"), ("material", "material"),
)  # fmt: skip
_SAFE_IMAGE = re.compile(r"^[A-Za-z0-9._-]+\.png$")


def _e(value: Any) -> str:
    """Escaped text for HTML (None as an en dash)."""
    return "\u2013" if value is None else html.escape(str(value), quote=True)


def _normalise(row: Mapping[str, Any]) -> dict[str, Any]:
    out = dict(row.to_dict() if hasattr(row, "to_dict") else row)
    details = row_details(out)
    out["details"] = details
    image = details.get("image")
    out["image"] = image if isinstance(image, str) and _SAFE_IMAGE.match(image) else None
    out["program"] = details.get("program") or out.get("program")
    out["protocol"] = details.get("protocol") or out.get("protocol") or DEFAULT_PROTOCOL
    if out.get("outcome") is None:
        out["outcome"] = "success" if out.get("success") else "failure"
    out["success"] = bool(out.get("success")) and out["outcome"] == "success"
    return out


def success_rates(rows: Iterable[Mapping[str, Any]], key: str) -> list[dict[str, Any]]:
    """Per value of ``key``: trials, successes, failures, errors and the success rate (0..1), by value."""
    groups: dict[str, dict[str, Any]] = {}
    for row in rows:
        value = row.get(key)
        name = "unknown" if value is None or value == "" else str(value)
        g = groups.setdefault(name, {key: name, "trials": 0, "success": 0, "failure": 0, "error": 0})
        g["trials"] += 1
        outcome = row.get("outcome") if row.get("outcome") in ("success", "failure", "error") else "failure"
        g[outcome] += 1
    out = []
    for name in sorted(groups):
        g = groups[name]
        g["rate"] = round(g["success"] / g["trials"], 4) if g["trials"] else None
        out.append(g)
    return out


def _fmt(value: Any, digits: int = 2) -> str:
    if value is None:
        return "\u2013"
    try:
        number = float(value)
    except (TypeError, ValueError):
        return _e(value)
    if math.isnan(number):
        return "\u2013"
    return f"{number:.{digits}f}"


def _plot(rates: list[dict[str, Any]], key: str, label: str, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = [r[key] for r in rates]
    values = [100.0 * (r["rate"] or 0.0) for r in rates]
    fig, ax = plt.subplots(figsize=(5.0, 0.35 * max(3, len(names)) + 1.0), dpi=100)
    bars = ax.barh(range(len(names)), values, color="#3b7dd8")
    ax.set_yticks(range(len(names)), labels=names)
    ax.invert_yaxis()
    ax.set_xlim(0, 100)
    ax.set_xlabel("success rate (%)")
    ax.set_title(f"Success rate by {label}")
    for bar, r in zip(bars, rates, strict=True):
        ax.text(
            min(bar.get_width() + 1, 88),
            bar.get_y() + bar.get_height() / 2,
            f"n={r['trials']}",
            va="center",
            fontsize=8,
        )
    fig.tight_layout()
    fig.savefig(path, format="png")
    plt.close(fig)


def _rate_table(rates: list[dict[str, Any]], key: str, label: str) -> str:
    body = "".join(
        f"<tr><td>{_e(r[key])}</td><td class='num'>{r['trials']}</td><td class='num'>{r['success']}</td>"
        f"<td class='num'>{r['error']}</td><td class='num'>{_fmt(100 * (r['rate'] or 0), 0)} %</td></tr>"
        for r in rates
    )
    return (
        f"<table><caption>by {_e(label)}</caption><thead><tr><th>{_e(label)}</th><th>trials</th><th>success</th>"
        f"<th>errors</th><th>rate</th></tr></thead><tbody>{body}</tbody></table>"
    )


def _outcome_class(r: dict[str, Any]) -> str:
    """The CSS class of a trial's outcome: an unknown outcome is shown as a failure."""
    return r["outcome"] if r["outcome"] in ("success", "failure", "error") else "failure"


def _row_html(r: dict[str, Any]) -> str:
    outcome = _outcome_class(r)
    return (
        f"<tr><td>{_e(r.get('object_name'))}</td><td class='num'>{_e(r.get('rank'))}</td>"
        f"<td>{_e(r.get('grasp_type'))}</td><td>{_e(r.get('family'))}</td><td class='num'>{_e(r.get('seed'))}</td>"
        f"<td class='{outcome}'>{_e(r.get('outcome'))}</td><td class='num'>{_fmt(r.get('slip_cm'))}</td>"
        f"<td class='num'>{_fmt(r.get('rotation_deg'), 1)}</td><td class='num'>{_fmt(r.get('grip_force_n'))}</td>"
        f"<td class='num'>{_fmt(r.get('max_contact_force_n'))}</td><td>{_e(r.get('reason'))}</td></tr>"
    )


def _figure(r: dict[str, Any], out_dir: Path, label: str) -> str:
    image = r.get("image")
    name = str(r.get("object_name"))
    if image and (out_dir / "images" / image).is_file():
        pic = f"<img src='images/{_e(image)}' alt='{_e(name)}: {_e(r.get('grasp_type'))}' loading='lazy'>"
    else:
        pic = "<div class='noimg'>no image rendered</div>"
    outcome = _outcome_class(r)
    return (
        f"<figure>{pic}<figcaption><b>{_e(name)}</b>: {_e(label)}<br>{_e(r.get('grasp_type'))} "
        f"({_e(r.get('family'))}; {_e(r.get('program'))} program): <span class='{outcome}'>"
        f"{_e(r.get('outcome'))}</span>, slip {_fmt(r.get('slip_cm'))} cm, turn {_fmt(r.get('rotation_deg'), 1)} deg"
        f"</figcaption></figure>"
    )


def _gallery(rows: list[dict[str, Any]], out_dir: Path, choices: list[Any]) -> str:
    """Per object: the first choice, and beside it the validated choice where it differs, or why none
    of the candidates holds."""
    first_row: dict[tuple, dict[str, Any]] = {}
    for r in rows:
        key = (str(r.get("object_name")), str(r.get("grasp_type")))
        if key not in first_row or (r.get("seed") or 0) < (first_row[key].get("seed") or 0):
            first_row[key] = r
    figures = []
    for c in sorted(choices, key=lambda c: c.object_name):
        first = first_row[(c.object_name, c.first)]
        parts = [_figure(first, out_dir, "first choice" + (" (validated)" if not c.differs else ""))]
        if c.validated is not None and c.differs:
            label = f"validated choice (planner's rank {c.validated_rank + 1})"
            parts.append(_figure(first_row[(c.object_name, c.validated)], out_dir, label))
        elif c.validated is None:
            causes = "; ".join(
                f"{t}: {failure_cause(first_row[(c.object_name, t)])}" for t, _ in c.reasons
            )
            parts.append(f"<p class='why'><b>{_e(c.object_name)}</b>: no candidate holds. {_e(causes)}</p>")
        figures.append(f"<div class='choice'>{''.join(parts)}</div>")
    return "\n".join(figures) or "<p>No trials.</p>"


def _csv_cell(value: Any) -> Any:
    """A CSV cell; text that a spreadsheet would run as a formula is escaped (:func:`kb.csvio.spreadsheet_cell`)."""
    value = to_jsonable(value)
    return spreadsheet_cell(value) if isinstance(value, str) else value


def write_report(
    results: Iterable[Mapping[str, Any]],
    out_dir: str | Path,
    *,
    title_meta: Mapping[str, Any] | None = None,
    now: Callable[[], _dt.datetime] = lambda: _dt.datetime.now(_dt.UTC),
) -> Path:
    """Write ``index.html``, plots, ``results.json`` and ``results.csv`` into ``out_dir``; return the
    path of ``index.html``. ``results`` are result rows (see the module docstring)."""
    from sim.choice import choose, summarize_choices

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    rows = sorted(
        (_normalise(r) for r in results),
        key=lambda r: (str(r.get("object_name")), r.get("rank") or 0, str(r.get("grasp_type")), r.get("seed") or 0),
    )
    total = len(rows)
    counts = {k: sum(r["outcome"] == k for r in rows) for k in ("success", "failure", "error")}
    objects = len({r.get("object_name") for r in rows})
    rates = {key: success_rates(rows, key) for key, _ in _GROUPS}
    generated = now().strftime("%Y-%m-%d %H:%M UTC")
    protocols = sorted({str(r["protocol"]) for r in rows})
    rate = counts["success"] / total if total else 0.0
    choices = choose(rows)
    chosen = summarize_choices(choices)
    template = Template(resources.files("sim").joinpath("templates/report.html").read_text(encoding="utf-8"))
    page = template.substitute(
        meta=_e(" \u00b7 ".join(_meta_bits(rows, generated, protocols, title_meta))),
        cards=_cards(rows, counts, chosen, objects, rate),
        plots="\n".join(_plots(rates, out)) or "<p>No trials.</p>",
        rate_tables="\n".join(_rate_table(rates[key], key, label) for key, label in _GROUPS),
        gallery=_gallery(rows, out, choices),
        rows="\n".join(_row_html(r) for r in rows),
    )
    index = out / "index.html"
    index.write_text(page, encoding="utf-8")
    summary = {"generated": generated, "objects": objects, "trials": total, **counts,
               "success_rate": round(rate, 4), "protocols": protocols, "choices": chosen.to_dict()}  # fmt: skip
    doc = {"summary": summary, "rates": rates, "choices": [c.to_dict() for c in choices], "results": rows}
    _write_data(out, doc, rows)
    return index


def _plots(rates: Mapping[str, Any], out: Path) -> list[str]:
    """One success-rate plot per group that has trials, written into ``out``; their ``<img>`` tags."""
    plots = []
    for key, label in _GROUPS:
        if not rates[key]:
            continue
        name = f"rates_by_{key}.png"
        _plot(rates[key], key, label, out / name)
        plots.append(f"<img src='{name}' alt='success rate by {_e(label)}'>")
    return plots


def _meta_bits(
    rows: list[dict[str, Any]], generated: str, protocols: list[str], title_meta: Mapping[str, Any] | None
) -> list[str]:
    """The report's header line: when, how many, the success rule judged by, simulator, hand, the caller's."""
    objects = len({r.get("object_name") for r in rows})
    versions = sorted({str(r.get("hand_version")) for r in rows if r.get("hand_version")})
    sims = sorted({str(r.get("simulator")) for r in rows if r.get("simulator")})
    bits = [f"generated {generated}", f"{objects} objects, {len(rows)} trials"]
    bits.append("protocol " + (", ".join(protocols) or DEFAULT_PROTOCOL))
    if sims:
        bits.append("simulator " + ", ".join(sims))
    if versions:
        bits.append("hand " + ", ".join(versions))
    bits += [f"{k} {v}" for k, v in (title_meta or {}).items()]
    return bits


def _cards(rows: list[dict[str, Any]], counts: Mapping[str, int], chosen: Any, objects: int, rate: float) -> str:
    """The summary cards: counts of trials by outcome (setup failures apart) and of objects by choice."""
    setup = sum(r["outcome"] == "failure" and is_setup_failure(r) for r in rows)  # counted apart
    return "".join(
        f"<div class='card'>{_e(label)}<b>{_e(value)}</b></div>"
        for label, value in (
            ("objects", objects),
            ("trials", len(rows)),
            ("success", counts["success"]),
            ("grasp failure", counts["failure"] - setup),
            ("setup failure (aperture)", setup),
            ("error", counts["error"]),
            ("success rate", f"{100 * rate:.0f} %"),
            ("first choice holds", f"{chosen.first_holds} / {objects}"),
            ("validated grasp", f"{chosen.validated} / {objects}"),
            ("validated differs from first", chosen.differs),
        )
    )


def _write_data(out: Path, doc: Mapping[str, Any], rows: list[dict[str, Any]]) -> None:
    """``results.json`` (the whole document) and ``results.csv`` (a row per trial) beside the page."""
    (out / "results.json").write_text(json.dumps(to_jsonable(doc), ensure_ascii=False, indent=1), encoding="utf-8")
    with (out / "results.csv").open("w", newline="", encoding="utf-8") as fh:
        writer = csv.DictWriter(fh, fieldnames=CSV_FIELDS, extrasaction="ignore")
        writer.writeheader()
        for r in rows:
            writer.writerow({k: _csv_cell(r.get(k)) for k in CSV_FIELDS})
