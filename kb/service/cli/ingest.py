"""`objrecall extract`, `objrecall ingest` and `objrecall demo-store`: product pages into the catalog."""

from __future__ import annotations

import contextlib
import re
import signal
import threading
from pathlib import Path
from typing import Annotated, Any

import typer

from kb.service.cli.common import DbOption, JsonOption, emit, resolve_db

#: Fields ``objrecall extract`` prints, in this order.
EXTRACT_FIELDS = (
    "name", "dims_cm", "dims", "mass_g", "package_dims_cm", "package_mass_g", "shipping_dims_cm",
    "shipping_mass_g", "set_count", "set_mass_g", "material", "shape", "adapter", "url", "canonical_url", "gtin",
    "warnings",
)  # fmt: skip


def register(app: typer.Typer) -> None:
    """Add this package's commands to the root app."""
    app.command("extract")(extract_command)
    app.command("ingest")(ingest_command)
    app.command("demo-store")(demo_store_command)


def _fetch(url: str):
    """The page at ``url`` as (body, content_type), through the polite fetcher (robots.txt, size cap)."""
    import requests

    from scrapers.fetcher import PoliteFetcher

    with requests.Session() as session:
        result = PoliteFetcher(session).fetch(url)
    return result.body or b"", result.content_type, result.final_url or url


def extract_record(page_or_url: str, explain: bool = False) -> dict[str, Any]:
    """The normalised record of a saved page or a URL, as the plain dict ``extract`` prints (with every
    candidate value and the chooser's decision about it under ``candidates`` when ``explain``)."""
    from scrapers.extract import extract_file, extract_page

    if re.match(r"https?://", page_or_url, re.IGNORECASE):
        body, content_type, final_url = _fetch(page_or_url)
        record = extract_page(body, final_url, content_type)
    else:
        record = extract_file(page_or_url)
    data = record.to_dict()
    out = {key: data.get(key) for key in EXTRACT_FIELDS}
    if explain:
        out["candidates"] = data.get("candidates", [])
    return out


def _fmt(key: str, value: Any) -> str:
    if value is None or value == []:
        return "-"
    if isinstance(value, float):
        return f"{value:g} g"
    if isinstance(value, int) and not isinstance(value, bool):
        return str(value)
    if key == "dims_cm":
        return " x ".join(f"{v:g}" for v in value) + " cm"
    if key == "dims":
        return ", ".join(f"{e['role']} {e['cm']:g} cm" for e in value)
    if key in ("package_dims_cm", "shipping_dims_cm"):
        return "; ".join(" x ".join(f"{v:g}" for v in p) + " cm" for p in value)
    if key in ("package_mass_g", "shipping_mass_g"):
        return "; ".join(f"{v:g} g" for v in value)
    return str(value)


def extract_command(
    page: Annotated[
        str,
        typer.Argument(
            metavar="PAGE_OR_URL", help="A saved page (.html, or .json for Shopify product JSON) or a URL."
        ),
    ],
    json_out: JsonOption = False,
    explain: Annotated[
        bool, typer.Option("--explain", help="Also show every candidate value and why it was or was not chosen.")
    ] = False,
) -> None:
    """Print the normalised product record of one page: dimensions (cm, largest first; the stated extents
    with their roles), mass (g), package values, material, shape, the adapter used and warnings."""
    data = extract_record(page, explain)
    if json_out:
        emit(data)
        return
    for key in EXTRACT_FIELDS:
        if key != "warnings":
            typer.echo(f"{key:16} {_fmt(key, data[key])}")
    for warning in data["warnings"]:
        typer.echo(f"warning          {warning}")
    for cand in data.get("candidates", []):
        value = _fmt("dims_cm" if cand["feature"] == "dims" else "mass_g", cand["value"])
        typer.echo(f"candidate        {cand['feature']} {value} [{cand['role']}, {cand['adapter']}] "
                   f"{cand['decision']} ({cand['text'][:60]!r})")


# ---------------------------------------------------------------------------------------------- ingest, demo-store
def ingest_command(
    sources: Annotated[
        Path, typer.Option("--sources", help="The sources file (TOML) listing the stores to read.")
    ],
    db: DbOption = None,
    base_url: Annotated[
        str | None,
        typer.Option("--base-url", help="Use this base URL for every store (e.g. a demo store's port)."),
    ] = None,
    delay: Annotated[
        float | None, typer.Option("--delay", help="Seconds between requests to one host, for every store.")
    ] = None,
    page_deadline: Annotated[
        float | None,
        typer.Option("--page-deadline", help="Seconds one page may take in all (retries included), every store."),
    ] = None,
    store_budget: Annotated[
        float | None,
        typer.Option("--store-budget", help="Seconds each store may take in this run; then its pages are skipped."),
    ] = None,
    json_out: JsonOption = False,
) -> None:
    """Fetch the stores' product pages, extract, validate and add them to the catalog with provenance
    (one short write transaction; a second run over unchanged pages changes nothing).

    Exit codes: 0 the run is ok or ok_with_errors (some pages or a sitemap failed, the rest was read: see
    errors and rejected); 1 an error before or while writing (a malformed sources file, a database that
    cannot be written: nothing changed); 2 a usage error; 3 the run failed: nothing was fetched because of
    failures (every store unreachable), recorded in ingestion_runs with status failed; 130 interrupted
    (Ctrl-C): the catalog is as before the run, or as after it when the run had already reached its end."""
    import sys

    import requests

    from kb.catalog import KnowledgeBase
    from scrapers.ingest import EXIT_CODES, run_ingestion
    from scrapers.sources import load_sources

    plan = load_sources(
        sources, base_url=base_url, delay_s=delay, max_page_s=page_deadline, budget_s=store_budget
    )
    kb = KnowledgeBase.open(resolve_db(db))
    bar = IngestProgress(enabled=not json_out and sys.stderr.isatty())
    with interrupts_seen() as seen, requests.Session() as session, bar as progress:
        report = run_ingestion(kb, plan, session=session, progress=progress)
    if seen:  # Ctrl-C whose KeyboardInterrupt Python dropped: the run went on to its end
        typer.echo(f"interrupted: ingestion run {report.run_id} had already run to its end; its result is kept",
                   err=True)  # fmt: skip
        raise typer.Exit(INTERRUPTED_EXIT)
    if json_out:
        emit(report)
    else:
        print_ingest_summary(report)
    if EXIT_CODES.get(report.status, 0):
        if not json_out:
            typer.echo(f"ingestion run {report.run_id} failed: nothing was fetched ({len(report.errors)} errors, "
                       f"{report.rejected} pages rejected)", err=True)  # fmt: skip
        raise typer.Exit(EXIT_CODES[report.status])


#: The exit code of an interrupted command (128 + SIGINT, typer's for Ctrl-C).
INTERRUPTED_EXIT = 130


@contextlib.contextmanager
def interrupts_seen():
    """Record each SIGINT as well as raising it (the list yielded is non-empty once one came). Python drops a
    KeyboardInterrupt raised while a garbage-collector callback runs ("Exception ignored in ..."), and the
    run then goes on to its end: the record lets the command still exit as interrupted. Nothing is
    installed off the main thread or where SIGINT is ignored (a background job)."""
    seen: list[int] = []
    previous = signal.getsignal(signal.SIGINT)
    if threading.current_thread() is not threading.main_thread() or previous == signal.SIG_IGN:
        yield seen
        return

    def record(signum, frame):
        seen.append(signum)
        if callable(previous):
            previous(signum, frame)
        raise KeyboardInterrupt

    signal.signal(signal.SIGINT, record)
    try:
        yield seen
    finally:
        signal.signal(signal.SIGINT, previous)


class IngestProgress:
    """A rich progress bar on stderr (a no-op when disabled), used as the ``progress`` callback."""

    def __init__(self, *, enabled: bool):
        self.enabled = enabled
        self.bar = None

    def __enter__(self):
        if not self.enabled:
            return None
        from rich.console import Console
        from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

        self.bar = Progress(
            TextColumn("ingest"),
            BarColumn(),
            MofNCompleteColumn(),
            TimeElapsedColumn(),
            TextColumn("{task.description}"),
            console=Console(stderr=True),
            transient=True,
        )
        self.bar.__enter__()
        self.task = self.bar.add_task("", total=None)
        return self

    def __call__(self, done: int, total: int, url: str) -> None:
        self.bar.update(self.task, completed=done, total=total, description=url[-60:])

    def __exit__(self, *exc) -> None:
        if self.bar is not None:
            self.bar.__exit__(*exc)


def print_ingest_summary(report) -> None:
    from rich.console import Console
    from rich.table import Table

    table = Table(title=f"ingestion run {report.run_id} ({report.status})", show_header=True)
    table.add_column("count")
    table.add_column("value", justify="right")
    rows = [
        ("pages", report.pages),
        ("fetched", report.fetched),
        ("not modified", report.not_modified),
        ("extracted", report.extracted),
        ("rejected", report.rejected),
        *((f"  {reason}", n) for reason, n in report.rejected_reasons.items()),
        ("new objects", report.new),
        ("updated objects", report.updated),
        ("observations added", report.observations_added),
        ("duration", f"{report.duration_s:.1f} s"),
        ("write transaction", f"{report.write_s * 1000:.0f} ms"),
        ("pages/s", f"{report.pages_per_s:.1f}"),
    ]
    for key, value in rows:
        table.add_row(key, str(value))
    console = Console()
    console.print(table)
    if report.new_objects:
        console.print("new: " + ", ".join(report.new_objects), soft_wrap=True)
    if report.updated_objects:
        console.print("updated: " + ", ".join(report.updated_objects), soft_wrap=True)
    for err in report.errors[:10]:
        console.print(f"error: {err['url']}: {err['reason']}", soft_wrap=True)


def demo_store_command(
    port: Annotated[int, typer.Option("--port", help="Port on 127.0.0.1 (0 picks a free one).")] = 8765,
    host: Annotated[str, typer.Option("--host", help="Address to bind.")] = "127.0.0.1",
    crawl_delay: Annotated[
        float, typer.Option("--crawl-delay", help="Crawl-delay robots.txt asks for (s).")
    ] = 0.25,
    slow_s: Annotated[float, typer.Option("--slow-s", help="How long the slow page takes (s).")] = 3.0,
) -> None:
    """Serve the demo storefront (product pages in every supported format, plus broken pages) until Ctrl-C."""
    from scrapers.demo_store import DemoStore

    store = DemoStore(host, port, crawl_delay=crawl_delay, slow_s=slow_s).start()
    typer.echo(
        f"demo store: {store.base_url}/ (sitemap {store.base_url}/sitemap.xml); Ctrl-C stops", err=True
    )
    typer.echo(store.base_url)
    store.serve_forever()
