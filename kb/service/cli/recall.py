"""`objrecall recall` and `objrecall evaluate`: descriptions to ranked catalog objects, and their scores."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any

import typer

from kb.service.cli.common import DbOption, JsonOption
from kb.service.http.settings import ENV_SOURCES

METRIC_HELP = (
    "Distance: jp (the paper's Joint Probability), euclidean, minkowski (p=4), cosine, kdtree, jplog (JP with "
    "sizes and mass in log units). Default: jplog with names, jp with --features-only."
)


def register(app: typer.Typer) -> None:
    """Add the recall and evaluate commands to the root app."""
    app.command("recall")(recall_command)
    app.command("evaluate")(evaluate_command)


def recall_command(
    text: Annotated[str | None, typer.Argument(help="The description, in quotes.")] = None,
    file: Annotated[
        Path | None,
        typer.Option("--file", help="CSV with a 'description' column: JSON Lines, one per row."),
    ] = None,
    top: Annotated[int, typer.Option("--top", min=1, help="How many matches to return.")] = 5,
    metric: Annotated[str | None, typer.Option("--metric", help=METRIC_HELP)] = None,
    features_only: Annotated[
        bool,
        typer.Option("--features-only", help="Ignore object names in the text (the paper's method)."),
    ] = False,
    lookup: Annotated[
        bool,
        typer.Option("--lookup", help="When the catalog does not know it (open set, or confidence below "
                     "0.5), search the stores of --sources, add what fits, and recall again."),
    ] = False,
    force_lookup: Annotated[
        bool, typer.Option("--force-lookup", help="Like --lookup, but ask the stores even after a good recall.")
    ] = False,
    sources: Annotated[
        Path | None,
        typer.Option("--sources", help=f"Stores for --lookup (TOML; stores with a 'search') [env {ENV_SOURCES}; "
                     "default: the bundled demo store's]"),
    ] = None,
    base_url: Annotated[
        str | None, typer.Option("--base-url", help="Point every store of --sources at this URL.")
    ] = None,
    budget: Annotated[
        float, typer.Option("--budget", help="Seconds a lookup may take (default 10).")
    ] = 10.0,
    max_pages: Annotated[
        int, typer.Option("--max-pages", help="Requests a lookup may make, over all stores (default 20).")
    ] = 20,
    db: DbOption = None,
    json_out: JsonOption = False,
) -> None:
    """Recall the catalog objects a description is about, nearest first, with the reasons.

    With --lookup, an object the catalog does not know is looked up in the stores' search first."""
    from kb.errors import DescriptionError, RecallError
    from kb.service.cli.common import resolve_db
    from recall.metrics import METRICS

    if (text is None) == (file is None):
        raise DescriptionError("give either a description TEXT or --file D.csv (not both)")
    if metric is not None and metric not in METRICS:
        raise RecallError(f"unknown metric {metric!r}; expected one of {', '.join(METRICS)}")
    options = dict(top=top, metric=metric, features_only=features_only)
    if lookup or force_lookup:
        plan = _lookup_sources(sources, base_url)
        limits = dict(budget_s=budget, max_pages=max_pages, force=force_lookup)
        _lookup_command(resolve_db(db), text, file, plan, {**options, **limits}, json_out)
    else:
        _recall_command(resolve_db(db), text, file, options, json_out)

def evaluate_command(
    catalog: Annotated[Path | None, typer.Option("--catalog", help="Catalog CSV (canonical header).")] = None,
    descriptions: Annotated[
        Path | None, typer.Option("--descriptions", help="CSV with columns object,description.")
    ] = None,
    open_set: Annotated[
        Path | None,
        typer.Option("--open-set", help="CSV with a 'description' column of objects NOT in the catalog."),
    ] = None,
    every_set: Annotated[
        bool, typer.Option("--all", help="One row per development set (recall.scoreboard) instead.")
    ] = False,
    blind: Annotated[bool, typer.Option("--blind", help="With --all: the blind sets too.")] = False,
    json_out: JsonOption = False,
) -> None:
    """Recall accuracy per metric (the paper's Fig. 5), the hybrid's, parse scores and every miss;
    with --all, top-1/top-3, open-set detection, false flags, Brier and ECE of every development set."""
    from kb.service.cli.common import emit
    from recall.evaluation import evaluate

    if every_set:
        _scoreboard_command(blind, json_out)
        return
    if catalog is None or descriptions is None:
        raise typer.BadParameter("give --catalog and --descriptions, or --all")
    for path in (catalog, descriptions, open_set):
        if path is not None and not path.is_file():
            raise FileNotFoundError(2, "No such file", str(path))
    report = evaluate(catalog, descriptions, open_set_csv=open_set)
    if json_out:
        emit(report.to_dict())
    else:
        _print_report(report)


def _recall_command(db: Path, text: str | None, file: Path | None, options: dict, json_out: bool) -> None:
    """``recall``: one description, or each of a CSV's, recalled from the catalog."""
    from kb.service.cli.common import emit, emit_lines
    from recall.descriptions import read_description_column
    from recall.engine import Recaller

    recaller = Recaller.from_db(db)
    if file is not None:
        rows = read_description_column(file)
        results = (recaller.recall_text(row, **options) for row in rows)
        if json_out:
            emit_lines(r.to_dict() for r in results)
        else:
            for row, result in zip(rows, results, strict=True):
                _print_result(result, title=row)
        return
    result = recaller.recall_text(text or "", **options)
    if json_out:
        emit(result.to_dict())
    else:
        _print_result(result)


def _lookup_sources(path: Path | None, base_url: str | None):
    """The sources a lookup asks: --sources, else $OBJRECALL_SOURCES, else the bundled demo store's."""
    import os

    from scrapers.demo_store import DEMO_SOURCES
    from scrapers.sources import load_sources

    chosen = path or (Path(os.environ[ENV_SOURCES]) if os.environ.get(ENV_SOURCES) else DEMO_SOURCES)
    return load_sources(chosen, base_url=base_url)


def _lookup_command(db: Path, text: str | None, file: Path | None, plan, options: dict, json_out: bool) -> None:
    """``recall --lookup``: each description recalled, looked up when needed, and recalled again."""
    import requests

    from kb.service.cli.common import emit, emit_lines
    from recall.descriptions import read_description_column
    from recall.lookup import recall_with_lookup

    rows = read_description_column(file) if file is not None else [text or ""]
    with requests.Session() as session:
        results = (recall_with_lookup(db, row, sources=plan, session=session, **options) for row in rows)
        if json_out and file is None:
            emit(next(results).to_dict())
        elif json_out:
            emit_lines(r.to_dict() for r in results)
        else:
            for row, result in zip(rows, results, strict=True):
                _print_lookup(result)
                _print_result(result.result, title=row if file is not None else None)


def _print_lookup(result) -> None:
    """What a lookup did, before the recall it led to."""
    from rich.console import Console
    from rich.markup import escape

    console = Console()
    if not result.looked_up:
        console.print(escape(f"Lookup: not needed ({result.message})"))
        return
    console.print(escape(f"Lookup ({result.why}): {result.message}"))
    stores = result.stores
    for answer in stores.stores if stores else []:
        said = answer.status + (f": {answer.reason}" if answer.reason else "")
        console.print(escape(f"  store {answer.store}: {said}; searched {', '.join(answer.queries) or '-'}"))
    for cand in stores.candidates if stores else []:
        console.print(escape(f"  page {cand.url}: {cand.name or '?'} -> {cand.outcome}"
                             + (f" ({cand.reason})" if cand.reason else "")))  # fmt: skip


def _fmt(value: Any) -> str:
    if value is None:
        return "?"
    if isinstance(value, float):
        return f"{value:g}"
    return str(value)


def _print_result(result, title: str | None = None) -> None:
    from rich.console import Console
    from rich.markup import escape

    console = Console()
    if title:
        console.print(f"[bold]{escape(title)}[/bold]")
    for line in _refusals(result):
        console.print(escape(line), style="yellow")
    if not result.matches:
        if result.not_in_catalog:
            console.print(escape(_verdict(result)))
        else:
            console.print("No feature or object name found in the description: nothing to recall.")
        return
    quals = result.query.get("qualifiers", {})
    described = ", ".join(
        f"{f}={_fmt(v)}" + (f" ({quals[f]})" if f in quals else "") for f, v in result.query["values"].items()
    )
    named = f"; named: {', '.join(result.named)}" if result.named else ""
    vague = f"; vague: {', '.join(result.vague)}" if result.vague else ""
    console.print(escape(f"Described: {described or 'no features'}{named}{vague}"))
    title = f"metric {result.metric}" + (" (features only)" if result.features_only else " + names")
    console.print(_match_table(result.matches, result, title))
    if result.same_kind:
        console.print(_match_table(result.same_kind, result, f"closest of the same kind ({result.same_kind_as})"))
    console.print(escape(_verdict(result)))


def _refusals(result) -> list[str]:
    """One line per stated value the parser refused ("a mug 501 kg": beyond the catalog's limits), so the
    table never looks as if the value had been used (``--json`` has them in ``parsed.refused``)."""
    refused = (result.parsed or {}).get("refused") or []
    return [f"Not used: {r['words']!r}: {r['reason']}; recalled without it." for r in refused]


def _match_table(matches, result, title: str):
    """Matches in ranking order: the score used for ranking (= features - name + vague), each stated
    feature's part, the name part and, when vague words were used, their part."""
    from rich.table import Table

    stated = list(result.query["values"])
    show_name = not result.features_only
    show_vague = bool(result.vague)
    table = Table(title=title)
    table.add_column("#", justify="right")
    table.add_column("object")
    table.add_column("score", justify="right")
    for feat in stated:
        table.add_column(feat, justify="right")
    if show_name:
        table.add_column("name", justify="right")
    if show_vague:
        table.add_column("vague", justify="right")
    for i, m in enumerate(matches, 1):
        name = m.name + (" (named)" if m.matched_by_name else "")
        cells = [f"{_fmt(m.features.get(f))} [dim]+{m.contributions.get(f, 0.0):.2f}[/dim]" for f in stated]
        extra = [f"-{m.name_part:.2f}" if m.name_part >= 0.005 else "0.00"] if show_name else []  # no "-0.00"
        extra += [f"+{m.vague_part:.2f}"] if show_vague else []
        table.add_row(str(i), name, f"{m.score:.3f}", *cells, *extra)
    return table


def _verdict(result) -> str:
    """One line: not in the catalog / not a close match / a guess / close match, the confidence and why
    (:func:`recall.verdict.verdict`, the same line as ``--json``'s, the HTTP API's and the web page's)."""
    from recall.verdict import verdict

    return verdict(result).text


def _scoreboard_command(blind: bool, json_out: bool) -> None:
    """``evaluate --all``: one row per set and mode (recall.scoreboard)."""
    from rich.console import Console
    from rich.table import Table

    from kb.service.cli.common import emit
    from recall.scoreboard import BLIND_SETS, DEVELOPMENT_SETS, scoreboard

    rows = scoreboard(DEVELOPMENT_SETS + (BLIND_SETS if blind else ()))
    if json_out:
        emit({"sets": [r.to_dict() for r in rows]})
        return
    table = Table(title="Recall on every description set (top-1/top-3 %; jp vs euclidean: features only)")
    cols = ("set", "mode", "n", "top-1", "top-3", "detected", "false flags", "Brier", "ECE", "jp / euclidean")
    for col in cols:
        table.add_column(col, justify="left" if col in ("set", "mode") else "right", no_wrap=True)
    for row in rows:
        fo = row.features_only_top1
        versus = f"{100 * fo.get('jp', 0):.1f} / {100 * fo.get('euclidean', 0):.1f}"
        for m in row.modes:
            detected = f"{m.detected}/{row.open_set_n}" if m.detected is not None else "-"
            table.add_row(
                row.name, m.mode, str(row.n), f"{100 * m.top1:.1f}", f"{100 * m.top3:.1f}", detected,
                f"{m.false_flags} ({_pct(m.false_flags, row.n)})", f"{m.brier:.3f}", f"{m.ece:.3f}", versus,
            )  # fmt: skip
    console = Console(width=140)
    console.print(table)
    _print_reliability(console, rows)


def _print_reliability(console, rows) -> None:
    """The reliability plot of each mode, pooled over the sets the confidence was fitted on and over the
    others (the held-out split; ``recall.scoreboard.CONFIDENCE_FIT_SETS``)."""
    from recall.calibration import pooled
    from recall.scoreboard import CONFIDENCE_FIT_SETS

    for mode in dict.fromkeys(m.mode for r in rows for m in r.modes):
        for split, fitted in (("fitted on", True), ("held out", False)):
            cals = [m.calibration for r in rows for m in r.modes
                    if m.mode == mode and m.calibration and (r.name in CONFIDENCE_FIT_SETS) == fitted]  # fmt: skip
            if cals:
                cal = pooled(cals)
                console.print(f"Reliability, {mode}, sets the confidence was {split}: Brier {cal.brier:.3f}, "
                              f"ECE {cal.ece:.3f} over {cal.n} results", highlight=False)  # fmt: skip
                for line in cal.plot():
                    console.print(f"  {line}", highlight=False)


def _pct(k: int, n: int) -> str:
    return f"{100.0 * k / n:.1f} %" if n else "-"


def _print_report(report) -> None:
    from rich.console import Console
    from rich.markup import escape
    from rich.table import Table

    from recall.engine import DEFAULT_METRIC
    from recall.evaluation import PAPER_TOP1

    console = Console()
    table = Table(title=f"Recall accuracy on {report.n} descriptions (the paper's Fig. 5)")
    for col in ("metric", "top-1", "top-3", "paper top-1"):
        table.add_column(col, justify="left" if col == "metric" else "right")
    for s in report.scores:
        label = s.metric if s.features_only else f"{s.metric} + names (hybrid)"
        if not s.features_only and s.metric == DEFAULT_METRIC[False]:
            label += ", default"
        paper = f"{PAPER_TOP1[s.metric]} %" if s.features_only and s.metric in PAPER_TOP1 else "-"
        table.add_row(label, f"{s.top1_pct:.1f} %", f"{s.top3_pct:.1f} %", paper)
    console.print(table)
    p = report.parse
    if p:
        cats = ", ".join(
            f"{k} {v:.0%}" for k, v in (p.get("category_accuracy") or {}).items() if v is not None
        )
        r2d = p.get("r2_dims")
        r2m = p.get("r2_mass")
        console.print(
            f"Parse: R² dimensions {_fmt(round(r2d, 3)) if r2d is not None else '-'}, "
            f"R² mass {_fmt(round(r2m, 3)) if r2m is not None else '-'}; category accuracy: {cats}"
        )
    flags = ", ".join(f"{mode} {k}/{report.n} ({_pct(k, report.n)})" for mode, k in report.false_flags.items())
    console.print(f"Open-set flags on these in-catalog descriptions (false-flag rate): {flags}")
    if report.open_set_n:
        flagged = ", ".join(
            f"{mode} {k}/{report.open_set_n} ({_pct(k, report.open_set_n)}; confidence >= 0.9: "
            f"{report.open_set_confident[mode]})"
            for mode, k in report.open_set.items()
        )
        console.print(f"Open-set descriptions flagged (detection rate): {flagged}")
    for mode in report.points:
        cal = report.calibration(mode)
        console.print(f"Confidence, {mode}: Brier {cal.brier:.3f}, ECE {cal.ece:.3f} over {cal.n} results")
        for line in cal.plot():
            console.print(f"  {line}", highlight=False)
    if report.unknown_objects:
        console.print(
            f"Skipped {len(report.unknown_objects)} description(s) of objects not in the catalog: "
            + ", ".join(sorted(set(report.unknown_objects)))
        )
    if report.misses:
        console.print(f"\n[bold]Misses ({len(report.misses)})[/bold]")
        for m in report.misses:
            line = escape(f"[{m.mode}] {m.object} -> {m.got}: {m.reason}")
            console.print(f"{line}\n    [dim]{escape(m.description)}[/dim]")
