"""Free-text fallback: sizes written in the product's name (``Panel 60 x 30 cm``, ``Table, 235x100 cm``)
and the page's title and canonical URL.

The lowest priority: a size in a name is often only two of three dimensions, or a variant's; it is
used only when nothing better states the dimensions, always with a note. The name itself comes from
here when structured data has none.
"""

from __future__ import annotations

from scrapers.adapters import Observation, adapter
from scrapers.page import Page
from scrapers.quantities import parse_dims

__all__ = ["text"]


@adapter("text", priority=90)
def text(page: Page) -> list[Observation]:
    """The page title (name, and a size written in it) and the canonical URL."""
    obs: list[Observation] = []
    title = page.title
    if title:
        obs.append(Observation("name", title, rank=2, raw=title))
        dims = parse_dims(title, None, page.decimal_comma)
        if dims:
            obs.append(
                Observation(
                    "dims",
                    dims[0].values_cm,
                    rank=2,
                    raw=title,
                    note=f"dimensions read from the product name ({title!r})",
                )
            )
    if page.canonical_url:
        obs.append(Observation("canonical_url", page.canonical_url, rank=2, raw=page.canonical_url))
    return obs
