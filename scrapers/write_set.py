"""Planning an ingestion run's write set: which catalog rows the extracted pages add or change.

Pure functions over plain rows (no database): the pages of one product grouped together
(:func:`group_pages`), each group matched to a catalog object or planned as a new one
(:func:`match_groups`), the observation rows each page contributes (:func:`observations_of`), the catalog
values fused from them (:func:`scrapers.fusion.fuse`, :func:`catalog_values`), which matched objects
really change (:func:`plan_update`), and the ``pages`` and ``page_events`` rows of the run.
:mod:`scrapers.catalog_write` executes the plan in one short write transaction.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from datetime import datetime
from typing import TYPE_CHECKING, Any

from kb.errors import InvalidFeature
from kb.features import DIMENSIONS, FEATURES, NUMERIC_FEATURES, ObjectRecord
from scrapers.fusion import Observation, fuse

if TYPE_CHECKING:  # the job's records; this module only reads their attributes
    from scrapers.outcomes import PageOutcome

__all__ = [
    "CatalogIndex",
    "as_observations",
    "catalog_values",
    "dedupe_rows",
    "event_rows",
    "group_pages",
    "match_groups",
    "naive",
    "observations_of",
    "page_rows",
    "plan_new",
    "plan_update",
]


def naive(ts: datetime | None) -> datetime | None:
    """``ts`` without its time zone (DuckDB TIMESTAMP columns are naive UTC)."""
    return ts.replace(tzinfo=None) if ts is not None and ts.tzinfo is not None else ts


def group_pages(pages: list[PageOutcome]) -> list[list[PageOutcome]]:
    """Pages of one product together: union of shared canonical URL, GTIN or normalised name."""
    parent = list(range(len(pages)))

    def find(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    owner: dict[tuple[str, str], int] = {}
    for i, page in enumerate(pages):
        keys = [("url", page.source), ("name", page.clean.name)]
        if page.record.gtin:
            keys.append(("gtin", page.record.gtin.lstrip("0")))
        for key in keys:
            if key in owner:
                parent[find(i)] = find(owner[key])
            else:
                owner[key] = i
    groups: dict[int, list[PageOutcome]] = {}
    for i, page in enumerate(pages):
        groups.setdefault(find(i), []).append(page)
    return list(groups.values())


@dataclass
class CatalogIndex:
    """The catalog's objects as the run finds them, and the keys a product is matched by."""

    objects: dict[int, dict[str, Any]]
    by_name: dict[str, int] = field(default_factory=dict)
    by_url: dict[str, int] = field(default_factory=dict)
    by_gtin: dict[str, int] = field(default_factory=dict)

    @classmethod
    def build(cls, objects: dict[int, dict[str, Any]], aliases: Iterable[tuple[str, int]]) -> CatalogIndex:
        index = cls(
            objects,
            by_name={o["name"]: oid for oid, o in objects.items()},
            by_url={o["canonical_url"]: oid for oid, o in objects.items() if o["canonical_url"]},
            by_gtin={o["gtin"].lstrip("0"): oid for oid, o in objects.items() if o["gtin"]},
        )
        for alias, oid in aliases:
            index.by_name.setdefault(alias, oid)
        return index


def match_groups(
    groups: list[list[PageOutcome]], index: CatalogIndex
) -> tuple[dict[int, list[PageOutcome]], list[list[PageOutcome]]]:
    """(matched object id -> its pages, groups that are new products): by canonical URL, then GTIN, then
    name or alias."""
    matched: dict[int, list[PageOutcome]] = {}
    fresh: list[list[PageOutcome]] = []
    for group in groups:
        oid = None
        for look in (
            lambda p: index.by_url.get(p.source),
            lambda p: index.by_gtin.get((p.record.gtin or "").lstrip("0")) if p.record.gtin else None,
            lambda p: index.by_name.get(p.clean.name),
        ):
            oid = next((o for o in map(look, group) if o is not None), None)
            if oid is not None:
                break
        if oid is None:
            fresh.append(group)
        else:
            matched.setdefault(oid, []).extend(group)
    return matched, fresh


def observations_of(page: PageOutcome) -> list[dict[str, Any]]:
    """The observation rows one page contributes (without object id, run id)."""
    rec, raw = page.clean, page.record.raw
    rows = []
    for feat, value in rec.known_features().items():
        numeric = feat in NUMERIC_FEATURES
        text = (
            raw.get("dims") if feat in DIMENSIONS else raw.get("mass") if feat == "mass_g" else raw.get(feat)
        )
        rows.append(
            {
                "feature": feat,
                "value_num": float(value) if numeric else None,
                "value_text": None if numeric else str(value),
                "role": "product",
                "raw_text": (text or str(value))[:500],
            }
        )
    for i, pkg in enumerate(page.packages, start=1):
        for feat, value in pkg.items():
            text = raw.get("package_dims") if feat in DIMENSIONS else raw.get("package_mass")
            rows.append(
                {
                    "feature": feat,
                    "value_num": float(value),
                    "value_text": None,
                    "role": "package",
                    "raw_text": (f"package {i}: " + (text or f"{value:g}"))[:500],
                }
            )
    for row in rows:
        row.update(source=page.source, adapter=page.record.adapter, fetched_at=page.fetched_at)
    return rows


def signature(rows: Iterable[dict[str, Any]]) -> tuple:
    """What a set of observation rows says, order-free (a source that says the same again adds nothing)."""
    return tuple(
        sorted(
            (
                r["feature"],
                r["role"],
                None if r["value_num"] is None else round(float(r["value_num"]), 6),
                r["value_text"],
            )
            for r in rows
        )
    )


def dedupe_rows(rows: Iterable[dict[str, Any]]) -> list[dict[str, Any]]:
    """Drop exact repeats (the same source stating the same value twice, e.g. a duplicate route)."""
    seen, out = set(), []
    for r in rows:
        key = (r["source"], r["feature"], r["role"], r["value_num"], r["value_text"])
        if key not in seen:
            seen.add(key)
            out.append(r)
    return out


def rows_by_source(rows: list[dict[str, Any]]) -> list[list[dict[str, Any]]]:
    groups: dict[str, list[dict[str, Any]]] = {}
    for r in rows:
        groups.setdefault(r["source"], []).append(r)
    return list(groups.values())


def as_observations(rows: Iterable[dict[str, Any]]) -> list[Observation]:
    """Observation rows as :class:`scrapers.fusion.Observation` (rows without a value are skipped)."""
    out = []
    for r in rows:
        value = r["value_num"] if r["value_num"] is not None else r["value_text"]
        if value is None:
            continue
        out.append(
            Observation(
                feature=r["feature"],
                value=value,
                source=r["source"],
                role=r["role"],
                fetched_at=naive(r.get("fetched_at")),
                id=r.get("id") or 0,
                adapter=r.get("adapter"),
            )
        )
    return out


def catalog_values(
    fused: dict[str, Any], current: dict[str, Any], warnings: list[str], name: str
) -> dict[str, Any]:
    """Fused values over the current ones, checked and sorted by the catalog's rules. A fused value the
    catalog refuses (it cannot happen with validated observations, but old rows may predate a rule) keeps
    the current value, with a warning."""
    merged = {f: fused.get(f, current.get(f)) for f in FEATURES}
    try:
        return ObjectRecord.create("x", **merged).features()
    except InvalidFeature as err:
        warnings.append(f"{name}: fused {err}; kept the catalog's values")
        return ObjectRecord.create("x", **{f: current.get(f) for f in FEATURES}).features()


def plan_new(
    group: list[PageOutcome], warnings: list[str], now: datetime
) -> tuple[dict[str, Any], list[dict[str, Any]]]:
    """(the ``objects`` row, its observation rows) of a product the catalog does not hold yet: values
    fused from its pages alone."""
    first = group[0]
    rows = dedupe_rows(r for p in group for r in observations_of(p))
    fused = fuse(as_observations(rows))
    values = catalog_values(fused.values, {}, warnings, first.clean.name)
    warnings.extend(f"{first.clean.name}: {w}" for w in fused.warnings)
    row = {
        "name": first.clean.name,
        **values,
        "source": first.source,
        "gtin": next((p.record.gtin for p in group if p.record.gtin), None),
        "canonical_url": first.source,
        "created_at": now,
        "updated_at": now,
    }
    return row, rows


def _new_rows(group: list[PageOutcome], history: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """The group's observation rows from sources that say something else than in their last run."""
    last_run_of: dict[str, Any] = {}
    for h in history:
        if h["source"] not in last_run_of or (h["run_id"] or -1) > (last_run_of[h["source"]] or -1):
            last_run_of[h["source"]] = h["run_id"]
    latest_sig = {
        src: signature(h for h in history if h["source"] == src and h["run_id"] == rid)
        for src, rid in last_run_of.items()
    }
    added = []
    for rows_of_source in rows_by_source(dedupe_rows(r for p in group for r in observations_of(p))):
        if latest_sig.get(rows_of_source[0]["source"]) != signature(rows_of_source):
            added.extend(rows_of_source)
    return added


def plan_update(
    obj: dict[str, Any],
    group: list[PageOutcome],
    history: list[dict[str, Any]],
    run_id: int,
    warnings: list[str],
    now: datetime,
) -> tuple[dict[str, Any] | None, list[dict[str, Any]]]:
    """(the ``objects`` update row or None when nothing changes, the observation rows to add) for a
    catalog object ``obj`` matched by ``group``, given its observation ``history``."""
    added = _new_rows(group, history)
    if not added:
        return None, []
    # Curated values that never got an observation row become one now (fusion's "curated source").
    observed = {h["feature"] for h in history if h["role"] == "product"}
    baseline = [
        {
            "feature": f,
            "value_num": float(obj[f]) if f in NUMERIC_FEATURES else None,
            "value_text": None if f in NUMERIC_FEATURES else str(obj[f]),
            "role": "product",
            "source": obj["source"] or "catalog",
            "adapter": "catalog",
            "fetched_at": obj["updated_at"],
            "raw_text": f"catalog value before ingestion run {run_id}",
        }
        for f in FEATURES
        if obj[f] is not None and f not in observed and f in {r["feature"] for r in added}
    ]
    added = baseline + added
    fused = fuse(as_observations([*history, *added]))
    warnings.extend(f"{obj['name']}: {w}" for w in fused.warnings)
    values = catalog_values(fused.values, obj, warnings, obj["name"])
    first = group[0]
    update = {
        "id": obj["id"],
        **values,
        "gtin": obj["gtin"] or next((p.record.gtin for p in group if p.record.gtin), None),
        "canonical_url": obj["canonical_url"] or first.source,
        "updated_at": now,
    }
    return update, added


def page_rows(
    outcomes: list[PageOutcome], object_of_page: dict[str, int], run_id: int, now: datetime
) -> tuple[list[dict[str, Any]], list[dict[str, Any]], list[dict[str, Any]]]:
    """(rows of not-modified pages, rows of pages that could not be fetched, rows of the other pages) for
    the ``pages`` table: validators for next time, keyed by the page's identity. A not-modified page keeps
    its object and hash; a page that could not be fetched (a time-out, a spent store budget) keeps its
    object, hash and validators and gets only its error (nothing was learnt about it)."""
    seen, unfetched, others = [], [], []
    for p in outcomes:
        row = {
            "url": p.key,
            "canonical_url": p.source if p.record is not None else None,
            "etag": p.etag,
            "last_modified": p.last_modified,
            "content_sha256": p.content_sha256,
            "status": p.status,
            "fetched_at": naive(p.fetched_at) or now,
            "object_id": object_of_page.get(p.url),
            "error": f"{p.reason}: {p.detail}" if p.outcome == "rejected" else None,
            "run_id": run_id,
        }
        if p.outcome == "not_modified":
            seen.append(row)
        elif p.outcome == "rejected" and p.stage == "fetch":
            unfetched.append(row)
        else:
            others.append(row)
    return seen, unfetched, others


def event_rows(
    outcomes: list[PageOutcome], events: list[tuple[str, str, str]], run_id: int, now: datetime
) -> list[dict[str, Any]]:
    """``page_events`` rows: each rejected page with its stage and reason, and the run's other errors."""
    return [
        {
            "run_id": run_id,
            "url": p.url,
            "stage": p.stage,
            "reason": f"{p.reason}: {p.detail}",
            "occurred_at": naive(p.fetched_at) or now,
        }
        for p in outcomes
        if p.outcome == "rejected"
    ] + [
        {"run_id": run_id, "url": url, "stage": stage, "reason": reason, "occurred_at": now}
        for url, stage, reason in events
    ]
