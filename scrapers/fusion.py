"""How the catalog value of a feature is fused from its observations (the provenance rows).

Every value a source ever stated about an object is kept in ``observations`` (feature, value, role,
source, adapter, time, raw text, run). The value the catalog shows in ``objects`` is fused from them by
this rule, the same for every object:

1. **Product values only.** Observations with role ``package`` (shipping box, per-package lists) are kept
   for provenance but never become catalog values: the robot grasps the product, not its box.
2. **One vote per source: its latest.** For each (source, feature) only the most recent observation
   counts (latest ``fetched_at``, then highest id). A store that changes its page supersedes its own old
   value; a store that repeats itself does not outvote the others. A source is a page's canonical URL, or
   for curated data its file (``csv:seed_catalog.csv``).
3. **Curated values stand.** When a curated source (a catalog file, a person: :func:`is_curated`)
   states a feature, only curated sources vote on it: a store's value never replaces a curated one, it is
   kept in ``observations`` and, when it differs by more than :data:`DISAGREEMENT_RATIO` (or names
   another word), a warning says so. Stores fill the features no curated source states (a partial size
   stays partial where nobody states the rest).
5. **Numbers: the median** of those latest values (the mean of the two middle ones for an even count).
   One wrong source among three cannot move the value; with two sources the value lies between them. The
   medians of ``a``, ``b`` and ``c`` keep ``a >= b >= c`` when every source states all three (each
   source's values are sorted); the catalog sorts them again in case a source stated fewer.
6. **Words** (material, shape, ...): the value most sources state; a tie goes to the curated source
   (anything that is not a web page) and then to the most recent observation.
4. **A lookup's values are provisional.** Observations made by an on-demand lookup (adapter
   ``lookup:<extractor>``, see :func:`is_provisional`) count for a feature only when no other source states
   it: one page found by one search must not move a curated value or one the nightly crawl observes
   again every night. When only lookup pages state a feature, they are fused like any other sources.
7. **Disagreement is reported, not hidden:** when the largest and smallest latest values of a number
   differ by more than :data:`DISAGREEMENT_RATIO`, or sources state different words, a warning names the
   feature, the values and their sources.

Features no source observed keep whatever value the catalog already has (texture, fragility and rigidity
come from curated data, not from storefronts).
"""

from __future__ import annotations

import statistics
from collections.abc import Iterable
from dataclasses import dataclass, field
from datetime import datetime
from typing import Any

from kb.features import CATEGORICAL_FEATURES, NUMERIC_FEATURES

__all__ = ["DISAGREEMENT_RATIO", "LOOKUP_ADAPTER_PREFIX", "FusedValues", "Observation", "fuse", "is_curated",
           "is_provisional"]

#: Largest/smallest ratio above which sources are said to disagree about a number.
DISAGREEMENT_RATIO = 1.10
#: The adapter of an observation made by an on-demand lookup starts with this (``lookup:jsonld``).
LOOKUP_ADAPTER_PREFIX = "lookup:"


@dataclass(frozen=True)
class Observation:
    """One observed value (a row of the ``observations`` table)."""

    feature: str
    value: float | str
    source: str
    role: str = "product"
    fetched_at: datetime | None = None
    id: int = 0
    adapter: str | None = None


@dataclass
class FusedValues:
    """The fused value per feature, how many sources backed it, and the disagreements found."""

    values: dict[str, Any] = field(default_factory=dict)
    support: dict[str, int] = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)


def is_curated(source: str) -> bool:
    """Curated data (a catalog file, a person) rather than a web page."""
    return not source.startswith(("http://", "https://"))


def is_provisional(obs: Observation) -> bool:
    """Observed by an on-demand lookup (rule 5): outranked by any curated or crawled observation."""
    return (obs.adapter or "").startswith(LOOKUP_ADAPTER_PREFIX)


def _order(o: Observation) -> tuple:
    return (o.fetched_at or datetime.min, o.id)


def latest_per_source(observations: Iterable[Observation]) -> dict[str, dict[str, Observation]]:
    """feature -> source -> that source's latest product observation of the feature (rules 1 and 2)."""
    latest: dict[str, dict[str, Observation]] = {}
    for obs in observations:
        if obs.role != "product":
            continue
        by_source = latest.setdefault(obs.feature, {})
        current = by_source.get(obs.source)
        if current is None or _order(obs) > _order(current):
            by_source[obs.source] = obs
    return latest


def _web_disagreement(feature: str, curated: list[Observation], web: list[Observation]) -> str | None:
    """A warning when web sources state something else than the curated value of ``feature`` (rule 3)."""
    if not web:
        return None
    if feature in NUMERIC_FEATURES:
        numbers = [float(o.value) for o in curated + web]
        lo, hi = min(numbers), max(numbers)
        if not (lo > 0 and hi / lo > DISAGREEMENT_RATIO):
            return None
    elif {str(o.value) for o in web} <= {str(o.value) for o in curated}:
        return None
    stated = ", ".join(f"{o.value:g}" if isinstance(o.value, float) else f"{o.value}" for o in web)
    kept = ", ".join(f"{o.value:g}" if isinstance(o.value, float) else f"{o.value}" for o in curated)
    return f"stores state {feature} {stated}; kept the curated {kept}"


def fuse(observations: Iterable[Observation]) -> FusedValues:
    """The catalog values the observations support (see the module docstring for the rule)."""
    out = FusedValues()
    for feature, by_source in latest_per_source(observations).items():
        votes = list(by_source.values())
        curated = [o for o in votes if is_curated(o.source)]
        if curated and len(curated) < len(votes):  # rule 3: curated values stand
            warning = _web_disagreement(feature, curated, [o for o in votes if not is_curated(o.source)])
            if warning:
                out.warnings.append(warning)
            votes = curated
        settled = [o for o in votes if not is_provisional(o)]
        votes = settled or votes  # rule 4: lookup values only where nothing else is known
        if feature in NUMERIC_FEATURES:
            numbers = [float(o.value) for o in votes]
            out.values[feature] = statistics.median(numbers)
            lo, hi = min(numbers), max(numbers)
            if lo > 0 and hi / lo > DISAGREEMENT_RATIO:
                stated = ", ".join(f"{float(o.value):g} ({o.source})" for o in sorted(votes, key=_order))
                out.warnings.append(f"sources disagree on {feature}: {stated}; using the median")
        elif feature in CATEGORICAL_FEATURES:
            counts: dict[str, int] = {}
            for o in votes:
                counts[str(o.value)] = counts.get(str(o.value), 0) + 1
            best = max(counts.values())
            tied = [o for o in votes if counts[str(o.value)] == best]
            winner = max(tied, key=lambda o: (is_curated(o.source), _order(o)))
            out.values[feature] = str(winner.value)
            if len(counts) > 1:
                stated = ", ".join(f"{o.value} ({o.source})" for o in sorted(votes, key=_order))
                out.warnings.append(f"sources disagree on {feature}: {stated}; using {winner.value!r}")
        else:
            continue
        out.support[feature] = len(votes)
    return out
