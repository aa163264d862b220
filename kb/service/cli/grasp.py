"""`objrecall grasp ...` commands: plan grasps for a description or a catalog CSV, validate them in MuJoCo.

- ``objrecall grasp plan "DESCRIPTION" [--json] [--simulate]``: recall the object, plan its grasps,
  optionally simulate the best one.
- ``objrecall grasp plan --catalog C.csv --json``: JSON Lines, one object per CSV row, in order.
- ``objrecall grasp validate [NAMES... | --all] [--workers N] [--report DIR] [--executor local|ray]``.

MuJoCo, matplotlib and Ray are imported inside the command bodies (``objrecall --help`` stays fast).
"""

from __future__ import annotations

import csv
from collections.abc import Iterator
from pathlib import Path
from typing import Annotated, Any

import typer

from kb.errors import (
    CatalogError,
    CatalogMissing,
    InvalidFeature,
    ObjectNotFound,
    ObjrecallError,
    RecallError,
)
from kb.service.cli.common import DbOption, JsonOption, emit, emit_lines, resolve_db

grasp_app = typer.Typer(no_args_is_help=True, help="Plan grasps for objects and validate them in MuJoCo.")


def plan_dict(plan: Any) -> dict[str, Any]:
    """A plan as JSON-ready data."""
    d = plan.to_dict()
    d["rationale"] = list(plan.rationale)
    return d


#: Header words accepted besides the canonical ones (the paper's table says "stiffness" for rigidity).
HEADER_ALIASES = {
    "object": "name",
    "a": "a_cm",
    "b": "b_cm",
    "c": "c_cm",
    "mass": "mass_g",
    "weight_g": "mass_g",
    "stiffness": "rigidity",
}


def catalog_plans(path: Path, *, top: int = 3) -> list[dict[str, Any]]:
    """Plans for every row of a catalog CSV, in order: one dict per row with ``name`` (as written in the
    file), the best plan's ``grasp_type`` and ``family`` (and its details), and the ranked ``alternatives``.

    Read leniently: only ``name`` is required; missing columns and blank cells are unknown features,
    extra columns are ignored. An invalid value (a negative size, an unknown word) is treated as unknown
    and named in the row's ``warnings``; a row without a name gets ``error`` instead of a plan, so the
    output always has one line per row.
    """
    from sim.experience import saved_experience
    from sim.planner import plan_grasps

    out: list[dict[str, Any]] = []
    for lineno, row in _lenient_rows(path):
        name = row.get("name", "")
        obj, warnings, error = _lenient_record(name, row)
        if obj is None:
            out.append({"name": name, "row": lineno, "error": error})
            continue
        plans = plan_grasps(obj, top=top, experience=saved_experience())
        best = plans[0]
        line = {
            "name": name,
            "grasp_type": best.grasp_type,
            "family": best.family,
            "grasped_dim": best.grasped_dim,
            "aperture_cm": best.aperture_cm,
            "approach": best.approach,
            "grip_force_n": best.grip_force_n,
            "score": best.score,
            "rationale": list(best.rationale),
            "alternatives": [{"grasp_type": p.grasp_type, "family": p.family, "score": p.score} for p in plans[1:]],
        }
        if warnings:
            line["warnings"] = warnings
        out.append(line)
    return out


def _lenient_rows(path: Path) -> Iterator[tuple[int, dict[str, str]]]:
    """(line number, row) of a catalog CSV, with header words mapped to feature names (:data:`HEADER_ALIASES`)
    and cells stripped; the first non-blank cell wins when two columns map to one feature."""
    from kb.csvio import read_spreadsheet_cell
    from kb.features import FEATURES

    with Path(path).open(newline="", encoding="utf-8-sig") as fh:
        reader = csv.DictReader(fh)
        header = [h.strip().lower() for h in (reader.fieldnames or []) if h is not None]
        keys = {h: (h if h in (*FEATURES, "name") else HEADER_ALIASES.get(h, h)) for h in header}
        if "name" not in keys.values():
            raise CatalogError(f"{path}: no 'name' column in the header")
        for lineno, raw in enumerate(reader, start=2):
            row: dict[str, str] = {}
            for k, v in raw.items():
                if k is None or not isinstance(v, str | None):
                    continue
                key = keys.get(k.strip().lower(), k.strip().lower())
                if key not in row or not row[key]:
                    row[key] = read_spreadsheet_cell((v or "").strip())
            yield lineno, row


def _lenient_record(name: str, row: dict[str, str]) -> tuple[Any, list[str], str | None]:
    """(record, warnings, None) with each invalid value dropped and named in a warning, or (None, [], error)
    when the row cannot be a record at all (no name)."""
    from kb.features import FEATURES, ObjectRecord

    values: dict[str, Any] = {f: row.get(f) or None for f in FEATURES}
    warnings: list[str] = []
    for _ in range(len(FEATURES) + 1):
        try:
            return ObjectRecord.create(name, **values), warnings, None
        except InvalidFeature as err:
            if err.field in values and values[err.field] is not None:
                values[err.field] = None
            elif err.field == "dimensions":
                values.update(a_cm=None, b_cm=None, c_cm=None)
            else:
                return None, [], str(err)
            warnings.append(f"{err}: treated as unknown")
    return None, [], "too many invalid values"  # pragma: no cover - each round clears one value


def _recall(db: Path, description: str) -> tuple[Any, dict[str, Any]]:
    """The object a description refers to, and how it was found.

    An exact catalog name or alias wins; otherwise the recall engine (recall/engine.py) picks the closest
    catalog object; with no catalog at all, the features parsed from the description are planned for.
    """
    from kb.catalog import KnowledgeBase
    from kb.features import FEATURES, ObjectRecord

    if db.exists():
        kb = KnowledgeBase.open(db, read_only=True)
        try:
            return kb.get_object(description), {"method": "name"}
        except ObjectNotFound:
            pass
        from recall.engine import Recaller

        result = Recaller.from_db(db).recall_text(description, top=3)
        best = result.best
        if best is None:
            raise RecallError(f"could not recall an object from {description!r}: no usable features or names")
        from recall.target import grasp_target

        return grasp_target(result, kb.get_object)
    from recall.parser import parse

    parsed = parse(description)
    values = {k: v for k, v in parsed.to_dict().items() if k in FEATURES and v is not None}
    if not values:
        raise RecallError(
            f"no catalog at {db} and no features in {description!r}: create one with `objrecall init --seed`"
        )
    # a description's object is planned for, never stored: its values are not held to the catalog's limits
    return ObjectRecord.create("described object", plausible=False, **values), {"method": "parsed", "db": str(db)}


def plan(
    description: Annotated[
        str | None, typer.Argument(help="What the object is: a description or a catalog name.")
    ] = None,
    catalog: Annotated[
        Path | None,
        typer.Option(
            "--catalog", help="Plan for every row of this catalog CSV (JSON Lines).", dir_okay=False
        ),
    ] = None,
    top: Annotated[int, typer.Option("--top", min=1, max=15, help="How many ranked plans to give.")] = 3,
    simulate: Annotated[
        bool,
        typer.Option(
            "--simulate",
            help="Simulate every listed plan in MuJoCo (one trial each): first choice vs validated choice.",
        ),
    ] = False,
    seed: Annotated[int, typer.Option("--seed", help="Trial seed (with --simulate).")] = 0,
    db: DbOption = None,
    json_out: JsonOption = False,
) -> None:
    """Plan how a five-fingered hand should grasp an object: ranked grasps with their rationale."""
    from rich.console import Console

    console = Console()
    if catalog is not None:
        if description is not None:
            raise ObjrecallError("give a DESCRIPTION or --catalog, not both")
        rows = catalog_plans(catalog, top=top)
        if json_out:
            emit_lines(rows)
        else:
            _print_catalog_plans(console, rows)
        return
    if description is None or not description.strip():
        raise ObjrecallError("give a DESCRIPTION of the object (or --catalog FILE.csv)")
    from sim.experience import saved_experience
    from sim.planner import plan_grasps

    obj, how = _recall(resolve_db(db), description.strip())
    plans = plan_grasps(obj, top=top, experience=saved_experience())
    out: dict[str, Any] = {
        "description": description,
        "object": obj.name,
        "recalled": how,
        "features": obj.features(),
        "plans": [plan_dict(p) for p in plans],
    }
    if simulate:
        from sim.choice import simulate_plans
        from sim.diagnosis import failure_cause

        trials, choice = simulate_plans(obj, plans, seed=seed)
        out["trials"] = [t.to_dict() for t in trials]
        for p, t in zip(plans, out["trials"], strict=True):  # why each failed one failed (sim/diagnosis.py)
            if not t["success"]:
                t["why"] = failure_cause({**t, "details": {"plan": p.to_dict()}})
        out["trial"] = out["trials"][0]  # the first choice's trial
        out["choice"] = choice.to_dict()
    if json_out:
        emit(out)
    else:
        _print_plans(console, obj, how, plans, out.get("trials"), out.get("choice"))


def _print_catalog_plans(console, rows: list[dict[str, Any]]) -> None:
    """``grasp plan --catalog``: one table row per CSV row, errors in red."""
    from rich.table import Table

    table = Table("name", "grasp type", "family", "aperture cm", "force N", "alternatives")
    for r in rows:
        if "error" in r:
            table.add_row(r["name"], "[red]error[/]", "", "", "", r["error"])
        else:
            alts = ", ".join(a["grasp_type"] for a in r["alternatives"])
            table.add_row(
                r["name"], r["grasp_type"], r["family"], f"{r['aperture_cm']:g}", f"{r['grip_force_n']:g}", alts
            )
    console.print(table)


def _print_plans(console, obj, how: dict[str, Any], plans, trials, choice) -> None:
    """``grasp plan``: the object and how it was found, each plan with its rationale, and with
    ``--simulate`` each plan's trial and the first vs validated choice."""
    from rich.markup import escape

    conf = f", confidence {how['confidence']:.2f}" if "confidence" in how else ""
    console.print(f"[bold]{escape(obj.name)}[/] ({how['method']}{conf})", highlight=False)
    if "why" in how:
        console.print(escape(how["why"]), highlight=False)
    for i, p in enumerate(plans, start=1):
        console.print(
            f"{i}. [bold]{p.grasp_type}[/] ({p.family}), across {p.grasped_dim} with {p.aperture_cm:g} cm aperture, "
            f"{p.approach} approach, {p.grip_force_n:g} N, score {p.score:g}"
        )
        for line in p.rationale:
            console.print(f"     - {line}", markup=False, highlight=False)
        if trials is not None:
            t = trials[i - 1]
            console.print(
                f"     trial ({t.get('program')} program): [bold]{t.get('outcome')}[/] "
                f"{escape(t.get('reason') or '')}; slip {t.get('slip_cm')} cm, turn {t.get('rotation_deg')} deg",
                highlight=False,
            )
            if t.get("why"):
                console.print(f"     why: {escape(t['why'])}", highlight=False)
    if choice is not None:
        console.print(_choice_line(choice), highlight=False)


def _choice_line(c: dict[str, Any]) -> str:
    """'first choice ... ; validated choice ...': both named, never one silently for the other."""
    first = f"first choice {c['first']} " + ("holds" if c["first_holds"] else f"fails ({c['first_reason']})")
    if c["validated"] is None:
        return f"{first}; validated choice: none of the {c['candidates']} candidates holds"
    same = " (the same)" if not c["differs"] else f" (planner's rank {c['validated_rank'] + 1})"
    return f"{first}; validated choice {c['validated']}{same}"


def validate(
    names: Annotated[list[str] | None, typer.Argument(help="Catalog object names or aliases.")] = None,
    all_objects: Annotated[bool, typer.Option("--all", help="Validate every catalog object.")] = False,
    workers: Annotated[
        int | None, typer.Option("--workers", min=1, help="Parallel workers (default: all cores).")
    ] = None,
    report: Annotated[
        Path | None,
        typer.Option("--report", help="Write an HTML report (with JSON/CSV) here.", file_okay=False),
    ] = None,
    executor: Annotated[str, typer.Option("--executor", help="local (processes), serial or ray.")] = "local",
    address: Annotated[
        str | None, typer.Option("--address", help="Ray cluster address (with --executor ray).")
    ] = None,
    seed: Annotated[list[int] | None, typer.Option("--seed", help="Trial seed; repeat for several.")] = None,
    top: Annotated[int, typer.Option("--top", min=1, max=15, help="Candidate grasps per object.")] = 3,
    limit: Annotated[
        int | None, typer.Option("--limit", min=0, help="Stop after this many new trials.")
    ] = None,
    progress: Annotated[bool, typer.Option("--progress/--no-progress", help="Show a progress bar.")] = True,
    protocol: Annotated[
        str,
        typer.Option(
            "--protocol", help="Success rule: lift_push (pushes in turn) or six_direction (DexGraspBench's)."
        ),
    ] = "lift_push",
    db: DbOption = None,
    json_out: JsonOption = False,
) -> None:
    """Simulate the planned grasps of catalog objects, store every result, resume where it stopped."""
    from kb.catalog import KnowledgeBase
    from sim.executors import EXECUTORS
    from sim.protocols import protocol_named
    from sim.worker import validate as run_validation

    protocol_named(protocol)  # an unknown one is refused before the catalog is opened
    if executor not in EXECUTORS:
        raise ObjrecallError(f"--executor {executor!r}: expected one of {', '.join(EXECUTORS)}")
    if address and executor != "ray":
        raise ObjrecallError("--address is for --executor ray")
    if names and all_objects:
        raise ObjrecallError("give object NAMES or --all, not both")
    if not names and not all_objects:
        raise ObjrecallError("name the objects to validate, or pass --all")
    path = resolve_db(db)
    if not path.exists():
        raise CatalogMissing(path)
    kb = KnowledgeBase.open(path)
    summary = run_validation(
        kb,
        None if all_objects else list(names or []),
        top=top,
        seeds=seed or [0],
        workers=workers,
        executor=executor,
        address=address,
        report_dir=report,
        progress=progress and not json_out,
        limit=limit,
        protocol=protocol,
    )
    if json_out:
        emit(summary.to_dict())
    else:
        _print_validation(summary)


def _print_validation(summary) -> None:
    """``grasp validate``: the counts, the first vs validated choices that differ, the report's place."""
    from rich.console import Console
    from rich.markup import escape

    console = Console()
    console.print(
        f"{summary.objects} objects, {summary.trials} trials: {summary.skipped} already stored, {summary.ran} run "
        f"({summary.succeeded} success, {summary.failed} failure, {summary.errors} error) "
        f"on {summary.workers} {summary.executor} worker(s) in {summary.wall_time_s:.1f} s",
        highlight=False,
    )
    if summary.not_stored:
        console.print(f"[yellow]{summary.not_stored} trials raised unexpected errors and were not stored[/]")
    console.print(summary.choice_summary.describe(), highlight=False)
    from sim.diagnosis import failure_cause

    for c in summary.choices:
        if c.differs:
            console.print(f"  {escape(c.object_name)}: {_choice_line(c.to_dict())}", highlight=False)
        if c.validated is None:  # why, in the hand's terms (aperture, mass and friction, moment)
            first = next(r for r in summary.results if r["object_name"] == c.object_name and r["grasp_type"] == c.first)
            console.print(f"    why: {escape(failure_cause(first))}", highlight=False)
    if summary.report:
        console.print(f"report: {summary.report}", highlight=False)


def register(app: typer.Typer) -> None:
    """Add this package's commands to the root app."""
    grasp_app.command("plan")(plan)
    grasp_app.command("validate")(validate)
    app.add_typer(grasp_app, name="grasp")
