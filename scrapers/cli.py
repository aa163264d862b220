"""`objrecall` commands of the scrapers package (registered by kb/cli.py)."""

from __future__ import annotations

import re
from typing import Annotated, Any

import typer

from kb.cli_common import JsonOption, emit

#: Fields ``objrecall extract`` prints, in this order.
EXTRACT_FIELDS = (
    "name", "dims_cm", "mass_g", "package_dims_cm", "package_mass_g", "material", "shape", "adapter",
    "url", "canonical_url", "gtin", "warnings",
)  # fmt: skip


def register(app: typer.Typer) -> None:
    """Add this package's commands to the root app."""
    app.command("extract")(extract_command)


def _fetch(url: str):
    """The page at ``url`` as (body, content_type), through the polite fetcher (robots.txt, size cap)."""
    import requests

    from scrapers.fetcher import PoliteFetcher

    with requests.Session() as session:
        result = PoliteFetcher(session).fetch(url)
    return result.body or b"", result.content_type, result.final_url or url


def extract_record(page_or_url: str) -> dict[str, Any]:
    """The normalised record of a saved page or a URL, as the plain dict ``extract`` prints."""
    from scrapers.extract import extract_file, extract_page

    if re.match(r"https?://", page_or_url, re.IGNORECASE):
        body, content_type, final_url = _fetch(page_or_url)
        record = extract_page(body, final_url, content_type)
    else:
        record = extract_file(page_or_url)
    data = record.to_dict()
    return {key: data.get(key) for key in EXTRACT_FIELDS}


def _fmt(key: str, value: Any) -> str:
    if value is None or value == []:
        return "-"
    if isinstance(value, float):
        return f"{value:g} g"
    if key == "dims_cm":
        return " x ".join(f"{v:g}" for v in value) + " cm"
    if key == "package_dims_cm":
        return "; ".join(" x ".join(f"{v:g}" for v in p) + " cm" for p in value)
    if key == "package_mass_g":
        return "; ".join(f"{v:g} g" for v in value)
    return str(value)


def extract_command(
    page: Annotated[
        str, typer.Argument(help="A saved page (.html, or .json for Shopify product JSON) or a URL.")
    ],
    json_out: JsonOption = False,
) -> None:
    """Print the normalised product record of one page: dimensions (cm, largest first), mass (g),
    package values, material, shape, the adapter used and warnings."""
    data = extract_record(page)
    if json_out:
        emit(data)
        return
    for key in EXTRACT_FIELDS:
        if key != "warnings":
            typer.echo(f"{key:16} {_fmt(key, data[key])}")
    for warning in data["warnings"]:
        typer.echo(f"warning          {warning}")
