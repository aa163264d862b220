"""The real-page corpus: product pages captured by public projects, with labels read from each page.

Pages are not copied into this repository (their content belongs to the stores and comes from other
projects). ``tests/data/real_pages/manifest*.jsonl`` names each page's source (repository, path, commit,
sha256); ``scripts/real_pages.py materialize`` copies them from fetched snapshots into the cache folder
(:func:`cache_dir`: ``$OBJRECALL_REAL_PAGES`` or ``../real-pages`` beside the repository).
``labels*.jsonl`` holds the true values (the keys of ``../shared/storefront-pages/README.md`` plus
``not_product`` and ``layout``; see ``tests/data/real_pages/README.md``).

**Split by store, never by page.** :func:`store_group` folds a host to its store (``www.amazon.co.uk``
and ``amazon.de`` are one store: one layout); :func:`held_out` puts a store in the held-out part by the
sha1 of that name, a rule fixed before any tuning. The shared batches join the corpus under the same rule.
"""

from __future__ import annotations

import hashlib
import json
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any
from urllib.parse import urlsplit

from scrapers.labelled_pages import default_pages_dir

__all__ = [
    "CorpusPage",
    "ENV_CACHE",
    "HELD_OUT_MODULUS",
    "cache_dir",
    "held_out",
    "load_corpus",
    "load_manifest",
    "store_group",
]

ENV_CACHE = "OBJRECALL_REAL_PAGES"
CORPUS_DIR = Path(__file__).resolve().parents[1] / "tests" / "data" / "real_pages"
#: A store is held out when the first 8 hex digits of sha1(store) are 0 modulo this: about a third.
HELD_OUT_MODULUS = 3

#: Second-level labels under a country code that are not the store's name (``co.uk``, ``com.br``).
_GENERIC_SLD = frozenset({"co", "com", "net", "org", "ac", "gov", "ne", "or", "gob", "edu", "ltd", "plc"})


def cache_dir() -> Path:
    env = os.environ.get(ENV_CACHE)
    if env:
        return Path(env)
    return Path(__file__).resolve().parents[2] / "real-pages"


def store_group(url_or_host: str) -> str:
    """The store a page belongs to: the host's registrable name without its suffix.

    >>> store_group("https://www.amazon.co.uk/dp/X"), store_group("smile.amazon.de"), store_group("www2.hm.com")
    ('amazon', 'amazon', 'hm')
    """
    host = urlsplit(url_or_host).hostname if "//" in url_or_host else url_or_host
    labels = [part for part in (host or "").lower().strip(".").split(".") if part]
    if len(labels) >= 2:
        labels = labels[:-1]  # the top-level domain
        if len(labels) >= 2 and labels[-1] in _GENERIC_SLD:
            labels = labels[:-1]
    return labels[-1] if labels else ""


def held_out(store: str) -> bool:
    """Whether ``store`` (a :func:`store_group` name) is in the held-out part."""
    return int(hashlib.sha1(store.encode("utf-8")).hexdigest()[:8], 16) % HELD_OUT_MODULUS == 0


@dataclass(frozen=True)
class CorpusPage:
    id: str
    path: Path
    url: str
    store: str
    language: str
    source: dict[str, Any]
    truth: dict[str, Any] | None

    @property
    def held_out(self) -> bool:
        return held_out(self.store)


def _jsonl(paths) -> list[dict[str, Any]]:
    rows = []
    for path in sorted(paths):
        for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            if line.strip():
                try:
                    rows.append(json.loads(line))
                except json.JSONDecodeError as e:
                    raise ValueError(f"{path.name} line {n}: not JSON ({e.msg})") from None
    return rows


def load_manifest(folder: Path = CORPUS_DIR) -> list[dict[str, Any]]:
    """Every ``manifest*.jsonl`` row of ``folder``, in file order."""
    return _jsonl(Path(folder).glob("manifest*.jsonl"))


def load_corpus(
    folder: Path = CORPUS_DIR, cache: Path | None = None, *, shared: bool = True, labelled_only: bool = True
) -> list[CorpusPage]:
    """The corpus's pages present in ``cache``, with their labels (``truth``; None when unlabelled and
    ``labelled_only`` is false), plus the shared batches when ``shared`` and they are present."""
    cache = Path(cache) if cache is not None else cache_dir()
    labels = {row["id"]: row for row in _jsonl(Path(folder).glob("labels*.jsonl"))}
    pages = []
    for row in load_manifest(folder):
        path = cache / f"{row['id']}.html"
        truth = labels.get(row["id"])
        if not path.is_file() or (truth is None and labelled_only):
            continue
        store = row.get("store") or store_group(row.get("url") or "")
        pages.append(CorpusPage(row["id"], path, row.get("url") or "", store, row.get("language") or "", row, truth))
    if shared:
        pages.extend(_shared_pages())
    return pages


def _shared_pages() -> list[CorpusPage]:
    from scrapers.labelled_pages import load_labels

    root = default_pages_dir()
    pages = []
    for folder, batch in ((root, "shared1"), (root / "batch2", "shared2")):
        for page in load_labels(folder):
            pid = f"{batch}-{Path(page.truth['file']).stem}"
            # a page saved without its address: the store is the file name's second word
            # (``scrapely_icone_...``, ``pricechecker_amazon_...``)
            store = page.truth.get("store") or store_group(page.url) or page.truth["file"].split("_")[1]
            pages.append(CorpusPage(pid, page.path, page.url, store, page.truth.get("language") or "",
                                    {"source_repo": page.truth.get("source_repo"), "batch": batch}, page.truth))
    return pages
