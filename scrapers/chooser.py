"""The chooser: one product record from every adapter's observations (:func:`fuse`).

For the product's dimensions and for its mass separately, observations that agree (within
:data:`AGREE_TOLERANCE`, a shorter dimension list agreeing with part of a longer one) form a cluster; the
highest-scoring cluster wins (:mod:`scrapers.choice`: one scored decision over its reader, rank, support,
completeness and place on the page), its most complete member is the value, and every other cluster
becomes a warning. Package values are kept apart, as listed by the highest-priority adapter that states
any. Values outside ``kb.features`` limits are refused with a warning (``scrapers/EXTRACTION.md`` §3).
"""

from __future__ import annotations

import re

from kb.errors import ExtractionError, ImpossibleValues
from kb.features import MATERIALS, axes_from_extents
from kb.measures.text import clean_text
from scrapers import choice
from scrapers.adapters import ADAPTERS, Observation
from scrapers.normalize import (
    check_dims,
    check_mass,
    impossible_value,
    material_from_text,
    shape_from_dims,
    shape_from_name,
)
from scrapers.product_names import choose_name
from scrapers.records import ProductRecord
from scrapers.restatements import outranked_shop_fields, restated_elsewhere
from scrapers.sets import set_apart, set_size
from scrapers.value_forms import placeholder_size

__all__ = ["AGREE_TOLERANCE", "MAX_CANDIDATES", "MAX_DISAGREEMENTS", "fuse"]

#: Two values agree when they differ by at most this fraction (rounding of converted units).
AGREE_TOLERANCE = 0.02
#: Only the highest-priority candidates of a feature are fused, and only so many disagreements reported
#: (a page listing thousands of weights is a list, not a product page).
MAX_CANDIDATES = 200
MAX_DISAGREEMENTS = 5
#: A statement worth comparing (:func:`_without_partial_reads`): a number of two digits or more, or two
#: numbers (a lone "2" may well be written elsewhere on the page for another reason).
_STATED = re.compile(r"\d{2}|\d\D+\d")


def _priority(o: Observation) -> tuple[int, int, int]:
    return (_source_index(o), o.rank, o.order)


def _close(x: float, y: float) -> bool:
    return abs(x - y) <= AGREE_TOLERANCE * max(abs(x), abs(y))


def _dims_agree(a: tuple[float, ...], b: tuple[float, ...]) -> bool:
    short, long_ = (a, b) if len(a) <= len(b) else (b, a)
    remaining = list(long_)
    for v in short:
        hit = next((i for i, w in enumerate(remaining) if _close(v, w)), None)
        if hit is None:
            return False
        remaining.pop(hit)
    return True


def _fmt(value) -> str:
    if isinstance(value, tuple):
        return " x ".join(f"{v:g}" for v in value) + " cm"
    return f"{value:g} g"


def _candidate(o: Observation, decision: str) -> dict:
    """One candidate value as ``extract --explain`` shows it."""
    out = {
        "feature": o.feature,
        "value": list(o.value) if isinstance(o.value, tuple) else o.value,
        "role": _whose(o),
        "adapter": o.source,
        "rank": o.rank,
        "order": o.order,
        "text": o.raw[:120],
        "decision": decision,
    }
    if o.feature == "dims":
        out["extents"] = [{"role": r, "cm": v} for r, v in o.extents()]
    if o.note:
        out["note"] = o.note
    return out


def _choose(
    cands: list[Observation], agree, feature: str, warnings: list[str], decisions: list[dict] | None = None
) -> Observation | None:
    """The winning observation among valid candidates: the one scored decision of :mod:`scrapers.choice`;
    other clusters become warnings. Each candidate's fate is appended to ``decisions`` (``extract
    --explain``), with its cluster's number, features and score."""
    if not cands:
        return None
    ranked = sorted(cands, key=_priority)[:MAX_CANDIDATES]
    clusters = choice.choose(ranked, agree, _source_index, len(ADAPTERS))
    best = clusters[0]
    chosen = None if best.site_wide else best.value
    if decisions is not None:
        for i, c in enumerate(clusters):
            scored = {"cluster": i + 1, "score": round(c.score, 3), "features": c.features}
            for o in c.members:
                if c.site_wide:
                    why = f"not the product's: stated only in {_off_main_places(c.members)}"
                elif o is chosen:
                    why = "chosen: highest-scoring cluster (scrapers.choice)"
                    if feature == "dims" and len(c.members) > 1:
                        why += ", its most complete member"
                elif i == 0:
                    why = "agrees with the chosen value"
                else:
                    why = f"alternative: disagrees with the chosen value (cluster {i + 1}, lower score)"
                decisions.append(_candidate(o, why) | scored | ({"representative": True} if o is c.value else {}))
    if chosen is None:
        where = "site-wide blocks" if not any(o.hidden for o in best.members) else "hidden meta fields"
        warnings.append(f"{feature}: only {where} state one ({best.members[0].raw[:80]!r}); not used")
        return None
    for other in clusters[1 : 1 + MAX_DISAGREEMENTS]:
        o = other.members[0]
        warnings.append(
            f"{feature}: {o.source} also states {_fmt(o.value)} ({o.raw[:80]!r}); kept {_fmt(chosen.value)} "
            f"from {chosen.source} ({chosen.raw[:80]!r})"
        )
    if len(clusters) > 1 + MAX_DISAGREEMENTS:
        warnings.append(f"{feature}: and {len(clusters) - 1 - MAX_DISAGREEMENTS} more disagreeing values")
    return chosen


def _off_main_places(members: list[Observation]) -> str:
    """Where a cluster outside the main content is stated: site-wide blocks, hidden meta fields or both."""
    places = []
    if any(o.site_wide for o in members):
        places.append("a site-wide block (header, footer, nav, aside)")
    if any(o.hidden for o in members):
        places.append("a hidden meta field (a shop system's postage weight, shown nowhere on the page)")
    return " or ".join(places)


def _source_index(o: Observation) -> int:
    return next((i for i, a in enumerate(ADAPTERS) if a.name == o.source), len(ADAPTERS))


def _collapse_repeats(values: list) -> list:
    """[A, B, A, B] -> [A, B]: the same package list rendered twice (desktop and mobile layouts). A run
    of identical single packages ([A, A]) is kept: stores list identical packages one by one."""
    n = len(values)
    for size in range(2, n // 2 + 1):
        if n % size == 0 and values[:size] * (n // size) == values:
            return values[:size]
    return values


def _whose(o: Observation) -> str:
    """Whose value an observation is: the product's, its package's (the product in its box), the
    shipment's (gross, the parcel sent), or a part's or a capacity's."""
    if o.role in ("component", "capacity", "shipping", "variant", "name", "content"):
        return o.role
    return "package" if o.package else "product"


def _valid(
    observations: list[Observation], feature: str, whose: str, warnings: list[str], decisions: list[dict],
    refused: list[str] | None = None,
) -> list[Observation]:
    """The candidates of ``feature`` that are ``whose`` value (see :func:`_whose`) and pass the catalog
    limits; a part's or a capacity's value and a refused value get their decision (and a refusal its
    warning, and its reason appended to ``refused``)."""
    out = []
    for o in observations:
        if o.feature != feature:
            continue
        w = _whose(o)
        if w != whose:
            if whose == "product" and w in ("component", "capacity", "variant") and len(decisions) < MAX_CANDIDATES:
                part = f" ({o.part})" if o.part else ""
                decisions.append(_candidate(o, f"not the product's: a {w}'s value{part} ({o.raw[:60]!r})"))
            continue
        if feature == "dims":
            extents = sorted(o.extents(), key=lambda e: -e[1])
            o.value, o.roles = tuple(v for _, v in extents), tuple(r for r, _ in extents)
            reason = check_dims(o.value) or (
                "a shop system's placeholder size (1 x 1 x 1), not a measurement" if placeholder_size(o.raw) else None
            )
        else:
            reason = check_mass(o.value)
        if reason and len(decisions) < MAX_CANDIDATES:
            decisions.append(_candidate(o, f"refused: {reason}"))
        if reason and len(warnings) < MAX_CANDIDATES:
            prefix = "" if whose == "product" else f"{whose} "
            warnings.append(f"{prefix}{feature} from {o.source} refused: {reason} ({o.raw[:80]!r})")
        if reason and refused is not None:
            refused.append(reason)
        elif not reason:
            out.append(o)
    return _without_partial_reads(observations, out, feature, warnings, decisions, refused)


def _statement(raw: str) -> str:
    """The value part of an observation's page text (after its label), folded for comparison."""
    return clean_text(raw.split(": ", 1)[-1]).lower()


def _without_partial_reads(
    observations: list[Observation], valid: list[Observation], feature: str, warnings: list[str],
    decisions: list[dict], refused: list[str] | None,
) -> list[Observation]:
    """``valid`` without the candidates read from a statement that was refused as impossible elsewhere
    (a spec table's ``5000 x 8 x 8 cm`` refused, the same text in JSON-LD read as 8 cm): one statement of
    a feature is refused once, never replaced by a partial read of itself. Each dropped candidate gets
    its decision and warning."""
    impossible = {}
    kept = {id(o) for o in valid}
    for o in observations:
        if o.feature == feature and id(o) not in kept and o.raw:
            reason = check_dims(o.value) if feature == "dims" else check_mass(o.value)
            statement = _statement(o.raw)
            if reason and impossible_value(reason) and _STATED.search(statement):
                impossible.setdefault(statement, reason)
    if not impossible:
        return valid
    out = []
    for o in valid:
        page_text = clean_text(o.raw).lower()
        hit = next((s for s in impossible if s in page_text), None)
        if hit is None:
            out.append(o)
            continue
        reason = f"a partial read of a refused statement ({hit[:60]!r}: {impossible[hit]})"
        if len(decisions) < MAX_CANDIDATES:
            decisions.append(_candidate(o, f"refused: {reason}"))
        if len(warnings) < MAX_CANDIDATES:
            warnings.append(f"{feature} from {o.source} refused: {reason} ({o.raw[:80]!r})")
        if refused is not None:
            refused.append(impossible[hit])
    return out


def _packages(
    cands: list[Observation], feature: str, raw: dict[str, str], decisions: list[dict], whose: str = "package"
) -> list:
    """Package (or shipping) values as listed by the highest-priority adapter that states any, in page
    order."""
    if not cands:
        return []
    best_source = min(cands, key=_priority).source
    chosen = sorted((o for o in cands if o.source == best_source), key=lambda o: o.order)
    decisions.extend(
        _candidate(o, f"{whose} value, kept apart" if o.source == best_source else
                   f"{whose} value not listed: {best_source} lists them")
        for o in cands[:MAX_CANDIDATES]
    )  # fmt: skip
    raw[f"{whose}_{feature}"] = " | ".join(o.raw for o in chosen)[:500]
    return _collapse_repeats([o.value for o in chosen[:MAX_CANDIDATES]])


def _material(observations: list[Observation], raw: dict[str, str]) -> str | None:
    for o in sorted((o for o in observations if o.feature == "material"), key=_priority):
        material = o.value if o.value in MATERIALS else material_from_text(o.value)
        if material:
            raw["material"] = o.raw
            return material
    return None


def _name(observations: list[Observation], warnings: list[str]) -> tuple[str | None, str | None]:
    """The product's name (:func:`scrapers.product_names.choose_name`) among the candidates by rank, then
    adapter priority."""
    found = sorted((o for o in observations if o.feature == "name"), key=lambda o: (o.rank, _priority(o)))
    return choose_name([(o.source, str(o.value)) for o in found[:MAX_CANDIDATES]], warnings)


def _first(observations: list[Observation], feature: str, by_rank: bool = True):
    found = [o for o in observations if o.feature == feature]
    found.sort(key=(lambda o: (o.rank, _priority(o))) if by_rank else _priority)
    return found[0].value if found else None


def fuse(observations: list[Observation], url: str) -> ProductRecord:
    """One record from all adapters' observations (the rule is in the module doc)."""
    warnings = [str(o.value) for o in observations if o.feature == "warning"][:MAX_CANDIDATES]
    decisions: list[dict] = []
    raw: dict[str, str] = {}
    refused: dict[str, list[str]] = {"dims": [], "mass": []}
    chosen: dict[str, Observation | None] = {}
    for feature, agree in (("dims", _dims_agree), ("mass", _close)):
        valid = _valid(observations, feature, "product", warnings, decisions, refused[feature])
        for cand, other in restated_elsewhere(valid, observations, feature, agree):
            valid.remove(cand)  # "Pendant measures 5/16 x 3/4" beside "Pendant measures: 0.3125 x 0.75"
            decisions.append(_candidate(cand, f"not the product's: the page states it as a {_whose(other)}'s "
                                              f"({other.raw[:60]!r})"))
        for cand, other in outranked_shop_fields(valid, agree):
            valid.remove(cand)
            decisions.append(_candidate(cand, f"not used: a shop system's shipping field, the page labels the "
                                              f"product's ({other.raw[:60]!r})"))
        if not valid:  # a quantity written only in the product's name ("Almonds - 13oz")
            valid = _valid(observations, feature, "name", warnings, decisions, refused[feature])
            if valid and feature == "mass":  # beside it, a size row's net content says it too ("Size: 275g")
                valid = _valid(observations, feature, "content", warnings, decisions, refused[feature]) + valid
        chosen[feature] = _choose(valid, agree, feature, warnings, decisions)
    apart = {
        (whose, feature): _packages(_valid(observations, feature, whose, warnings, decisions), feature, raw,
                                    decisions, whose)
        for whose in ("package", "shipping") for feature in ("dims", "mass")
    }  # fmt: skip
    name, name_refusal = _name(observations, warnings)
    the_set = set_size(name)
    set_mass = set_apart(chosen, the_set, warnings, decisions)
    dims_obs, mass_obs = chosen["dims"], chosen["mass"]
    if dims_obs is None and mass_obs is None and set_mass is None and not any(apart.values()):
        what = f" for {name!r}" if name else ""
        reasons = "; ".join(warnings[:3])
        message = f"{url}: no product dimensions or mass found{what}" + (f" ({reasons})" if reasons else "")
        refusals = refused["dims"] + refused["mass"]
        if refusals:
            raise ImpossibleValues(message, refusals[0])
        raise ExtractionError(message)
    for o in (dims_obs, mass_obs):
        if o is not None:
            raw["dims" if o.feature == "dims" else "mass"] = o.raw
            if o.note:
                warnings.append(f"{o.feature}: {o.note}")
    dims = tuple(round(v, 4) for v in axes_from_extents(dims_obs.extents())) if dims_obs else None
    used = dims_obs or mass_obs
    adapter = (
        used.source
        if used
        else min((o for o in observations if o.feature in ("dims", "mass")), key=_priority).source
    )
    return ProductRecord(
        name=name,
        url=url,
        canonical_url=_first(observations, "canonical_url"),
        gtin=_first(observations, "gtin", by_rank=False),
        dims_cm=dims,
        dims=[{"role": r, "cm": round(v, 4)} for r, v in dims_obs.extents()] if dims_obs else [],
        mass_g=round(mass_obs.value, 4) if mass_obs else None,
        package_dims_cm=[tuple(round(v, 4) for v in p) for p in apart["package", "dims"]],
        package_mass_g=[round(m, 4) for m in apart["package", "mass"]],
        shipping_dims_cm=[tuple(round(v, 4) for v in p) for p in apart["shipping", "dims"]],
        shipping_mass_g=[round(m, 4) for m in apart["shipping", "mass"]],
        set_count=the_set[0] if the_set else None,
        set_mass_g=round(set_mass, 4) if set_mass is not None else None,
        material=_material(observations, raw),
        shape=shape_from_name(name) or shape_from_dims(dims),
        adapter=adapter,
        warnings=list(dict.fromkeys(warnings)),
        raw=raw,
        refused={f: r[0] for f, r in refused.items() if r and chosen[f] is None}
        | ({"name": name_refusal} if name_refusal else {}),
        candidates=decisions,
    )
