"""Look it up: when the catalog does not know the described object, ask the stores, add it, recall again.

>>> result = recall_with_lookup("catalog.duckdb", "a glazed ceramic teapot about 22 cm wide, 900 g",
...                             sources=load_sources("scrapers/demo_sources.toml"))   # doctest: +SKIP
>>> result.found, result.result.best.name, result.message                             # doctest: +SKIP

1. **Recall** the description from the catalog. A lookup is needed (:func:`lookup_reason`) when nothing is
   recalled, the recall says the object is not in the catalog (``not_in_catalog``: a noun the catalog does
   not have; or ``open_set``: nothing close), or its confidence is below
   ``threshold`` (:data:`LOOKUP_BELOW_CONFIDENCE`), or the first match is not the thing the subject names
   (:func:`unnamed_subject`: "peanut butter" recalled as a coffee can), or the text names a product the
   catalog's kind is not: a proper name or contents the match lacks (:mod:`recall.lookup_need`); ``force``
   looks it up anyway.
2. **Search words** (:func:`search_terms`): the description's subject phrase ("glazed ceramic teapot"),
   then its head noun alone ("teapot"); each store gets the first that lists products.
3. **The stores** (:func:`scrapers.lookup.search_stores`): the top results of every store with a search,
   fetched politely, extracted and validated like the nightly job's pages; a page **fits** when the
   description, recalled over that product alone, is a close match (not open set, mean relative error
   at most :data:`FIT_CLOSENESS`; with no stated feature, when the description names the product). The
   pages that fit are written as one ingestion run (provenance ``lookup``, provisional values).
4. **Recall again** from the catalog, and say what happened (:class:`LookupResult`).

Bounded by ``budget_s`` (default 10 s) on the clock passed in, counted from the end of the first recall:
the stores get the budget minus a reserve for writing and recalling again (:data:`RESERVE_S`, at most half
of the budget); ``max_pages`` bounds the requests.
"""

from __future__ import annotations

import math
import re
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import requests

from kb.errors import RecallError
from kb.features import NUMERIC_FEATURES, ObjectRecord
from recall.engine import Recaller, RecallResult
from recall.fit import THRESHOLDS, Trust, judge
from recall.lookup_need import (
    LOOKUP_BELOW_CONFIDENCE,
    contents_phrase,
    lookup_reason,
    phrase_words,
    unnamed_contents,
    unnamed_subject,
)
from recall.lookup_slots import stated_placements
from scrapers.fetcher import Clock, SystemClock
from scrapers.lookup import DEFAULT_MAX_PAGES, StoresLookup, search_stores
from scrapers.sources import Sources

__all__ = [
    "DEFAULT_BUDGET_S",
    "FIT_CLOSENESS",
    "LOOKUP_BELOW_CONFIDENCE",
    "LookupResult",
    "described_names",
    "lookup_reason",
    "recall_with_lookup",
    "search_terms",
    "unnamed_subject",
]

DEFAULT_BUDGET_S = 10.0
#: A store's product fits the description when its mean relative error over the stated features is at most
#: this: the recall's open-set threshold for an unnamed match (one rule, :mod:`recall.fit`).
FIT_CLOSENESS = THRESHOLDS[Trust.PLAIN]
#: Seconds of the budget kept for judging the pages, writing and recalling again (at most half the budget).
RESERVE_S = 2.0
NOT_FOUND = "no close match in the catalog, and none found in the stores"


@dataclass
class LookupResult:
    """A recall with (perhaps) a lookup: the recall ``before``, whether and why it was looked up, the
    stores' side (:class:`scrapers.lookup.StoresLookup`), the recall ``after`` (None when not looked up),
    whether the object was found, a one-line message, and the seconds spent per stage."""

    text: str
    before: RecallResult
    looked_up: bool = False
    why: str | None = None
    stores: StoresLookup | None = None
    after: RecallResult | None = None
    found: bool = True
    message: str = ""
    seconds: dict[str, float] = field(default_factory=dict)

    @property
    def result(self) -> RecallResult:
        """The recall to act on: after the lookup when there was one."""
        return self.after if self.after is not None else self.before

    def to_dict(self) -> dict[str, Any]:
        return {
            "text": self.text,
            "looked_up": self.looked_up,
            "why": self.why,
            "found": self.found,
            "message": self.message,
            "result": self.result.to_dict(),
            "before": _summary(self.before),
            "after": _summary(self.after) if self.after is not None else None,
            "stores": self.stores.to_dict() if self.stores is not None else None,
            "seconds": {k: round(v, 4) for k, v in self.seconds.items()},
        }


def _summary(result: RecallResult) -> dict[str, Any]:
    best = result.best
    return {"match": best.name if best else None, "confidence": result.confidence, "open_set": result.open_set}


def search_terms(result: RecallResult) -> tuple[str, ...]:
    """The search words to try, most specific first: the subject phrase, then its head noun (in English
    when the recall recognised the noun, ``described``); before both, the contents of "a <container> of
    <contents>" the recall's match does not name (:func:`recall.lookup_need.unnamed_contents`: a store
    sells "pasta sauce", not a jar). Units and generic nouns ("5 grams", "something") name nothing to
    search for."""
    phrase = phrase_words(result.text or "")
    described = result.described.english if result.described is not None else None
    noun = described or result.unknown_noun or (phrase[-1] if phrase else None)
    terms = [" ".join(phrase)] if phrase else []
    contents = contents_phrase(result.text or "")
    if contents and (result.best is None or unnamed_contents(result) is not None):
        terms.insert(0, " ".join(contents))
    if noun and noun not in terms:
        terms.append(noun)
    return tuple(terms)


def described_names(result: RecallResult, terms: tuple[str, ...], heads=frozenset()) -> tuple[str, ...]:
    """What the description calls the object, given to the product that fits best as aliases: the subject
    phrase searched for first (the first of ``terms``) as the text writes it, then the described noun and
    its English name (``described``), else the head noun searched for (the last of ``terms``). A product
    found by those words whose features fit is one; its store name may not say so (a title in another
    language, a keyword list, a model number), and the recall after the lookup, and later ones, must know
    the object by the words a person used; the whole phrase too, since a noun modifier the product's names
    lacked would make the recall doubt the match ("a *cabinet* knob" named "knob"). A one-word noun that
    is the head noun of catalog names (``heads``: "ball", "light") is not given alone: it would name the
    product before the catalog's own objects of that noun."""
    noun = result.described
    names = [noun.noun, noun.english] if noun is not None else list(terms[-1:])
    names = [n for n in names if " " in n or n not in heads]
    written = _as_written(terms[0], result.text or "") if terms else None
    if written:
        names.insert(0, written)
    return tuple(dict.fromkeys(names))


def _as_written(phrase: str, text: str) -> str | None:
    """``phrase`` (words made singular, :func:`recall.subject.subject_phrase`) as the text writes it
    ("mercede tail light" -> "mercedes tail light"), or None when the text does not hold it."""
    from kb.kinds import singular

    want = phrase.split()
    words = re.findall(r"[^\W_]+(?:-[^\W_]+)*", text.lower().replace("'", "").replace("\u2019", ""))
    for i in range(len(words) - len(want) + 1):
        window = words[i : i + len(want)]
        if [singular(w) for w in window] == want:
            return " ".join(window)
    return None


def fits(text: str | Any, record: ObjectRecord) -> tuple[bool, str, float]:
    """Whether the product ``record`` is the object described, why, and how close it is (the mean relative
    error over the features the product states: a feature its page does not state says nothing about
    which of several products that fit is the one; :func:`scrapers.lookup.search_stores` names the
    closest by the description's noun): the recall's own fit rule
    (:func:`recall.fit.judge`) on the description recalled over that product alone, with the store's name
    counting as no evidence either way (:attr:`recall.fit.Trust.PLAIN`: a title can be a keyword list, a
    URL path or another language, and the store's search already matched the words); with no stated
    feature, when the description names the product. ``text`` is the description or its parse
    (``recall.parser.parse``), so that many records cost one parse."""
    if isinstance(text, str):
        from recall.parser import parse

        text = parse(text)  # once for every placement
    record = _judged(record)
    three = all(d is not None for d in record.dims_cm)
    described = stated_placements(text) if three else [text]  # the description's extents, where allowed
    judged = [_fit_of(d, recaller, placed) for placed in placements(record)
              for recaller in [Recaller.from_records([placed])] for d in described]  # fmt: skip
    return min(judged, key=lambda j: (j[3], j[2]))[:3]


def _fit_of(parsed: Any, recaller: Recaller, record: ObjectRecord) -> tuple[bool, str, float, float]:
    """:func:`fits` for one placement of the record's extents (``recaller``: over it alone) and of the
    description's (:func:`recall.lookup_slots.stated_placements`), with the fit's score last (to choose)."""
    result = recaller.recall_parsed(parsed, top=1)
    if not result.matches:
        return False, "the description states nothing to compare", math.inf, math.inf
    if result.closeness is None:
        named = result.matches[0].matched_by_name
        return named, "named by the description" if named else "no stated feature and not named", 1.0, 0.0
    fit = judge(result.closeness, result.errors, Trust.PLAIN, result.unused)
    return fit.close, fit.reason, _closeness_stated(result.errors, record), fit.score


def _closeness_stated(errors: dict[str, float], record: ObjectRecord) -> float:
    """Which of several products that fit is the one: the mean relative error over the sizes and mass both
    the description and the product's page state, else over every feature the page states (1 when
    none). The numbers first: a page's category is one word its extractor chose of several ("Solid
    Plastic polycarbonate globe with metalised copper finish": plastic) and a description's category word
    can be loose ("a copper shade", a finish), while a size or mass is measured on both sides; a category
    match hid a 1.9x size miss ("45 cm across" against a 24 cm wall light, metal: 0.23, below an exact
    45 cm copper-finish shade's 0.25)."""
    stated = {f: e for f, e in errors.items() if getattr(record, f, None) is not None}
    numbers = [e for f, e in stated.items() if f in NUMERIC_FEATURES]
    kept = numbers or list(stated.values())
    return sum(kept) / len(kept) if kept else 1.0


def placements(record: ObjectRecord) -> list[ObjectRecord]:
    """``record`` with the extents its page states (fewer than three) in each of the size slots they can
    take, largest first as always: a page that states two extents does not say which two ("Width: 62 cm,
    Depth: 60 cm" of a chair 129 cm tall), and compared as the largest two they are off by the missing
    one (the chair's 62 cm against its 129 cm height). The fit takes the placement that fits best; the
    record written stays the page's. A record with three extents or none has one placement, itself."""
    from dataclasses import replace
    from itertools import combinations

    known = [d for d in record.dims_cm if d is not None]
    if not known or len(known) >= 3:
        return [record]
    out = []
    for slots in combinations(range(3), len(known)):
        dims: list[float | None] = [None, None, None]
        for slot, value in zip(slots, sorted(known, reverse=True), strict=True):
            dims[slot] = value
        out.append(replace(record, a_cm=dims[0], b_cm=dims[1], c_cm=dims[2]))
    return out


def _judged(record: ObjectRecord) -> ObjectRecord:
    """``record`` as the fit judges it: a shape class that is only what its sizes imply
    (:func:`scrapers.normalize.shape_from_dims`, used when the page states no shape) is no evidence
    beyond the sizes, which are compared themselves, and cannot tell a round object from a box ("a knob
    about 2 cm across", radial, is no misfit of a 2.9 x 2.1 x 2.1 cm knob the sizes call compact)."""
    from dataclasses import replace

    from scrapers.normalize import shape_from_dims

    dims = [d for d in record.dims_cm if d is not None]
    if record.shape is not None and record.shape == shape_from_dims(dims):
        return replace(record, shape=None)
    return record


def recall_with_lookup(
    db: str | Path,
    text: str,
    *,
    sources: Sources,
    session: requests.Session | None = None,
    clock: Clock | None = None,
    budget_s: float = DEFAULT_BUDGET_S,
    max_pages: int = DEFAULT_MAX_PAGES,
    threshold: float = LOOKUP_BELOW_CONFIDENCE,
    force: bool = False,
    top: int = 5,
    metric: str | None = None,
    features_only: bool = False,
) -> LookupResult:
    """Recall ``text`` from the catalog at ``db`` and, when needed (or ``force``), look it up in the stores
    of ``sources`` (see the module docstring). The network (``session``) and the clock are passed in."""
    if not budget_s > 0 or budget_s > 600:
        raise RecallError(f"the lookup time budget must be more than 0 and at most 600 s, not {budget_s}")
    if max_pages < 1 or max_pages > 200:
        raise RecallError(f"the lookup page budget must be 1 to 200 pages, not {max_pages}")
    clock = clock or SystemClock()
    options = dict(top=top, metric=metric, features_only=features_only)
    t0 = time.perf_counter()
    before = Recaller.from_db(db).recall_text(text, **options)
    out = LookupResult(text=text, before=before, seconds={"recall": time.perf_counter() - t0})
    start = clock.monotonic()
    names = Recaller.from_db(db).names
    out.why = lookup_reason(before, threshold, names) or ("forced" if force else None)
    if out.why is None:
        out.message = f"recalled from the catalog: {before.best.name} (confidence {before.confidence:.2f})"
        return out
    terms = search_terms(before)
    if not terms:
        out.found, out.message = False, f"{NOT_FOUND}: the description names no object to search for"
        return out
    out.looked_up = True
    from kb.catalog import KnowledgeBase

    t0 = time.perf_counter()
    kb = KnowledgeBase.open(db)
    out.seconds["open"] = time.perf_counter() - t0
    deadline = start + budget_s - min(RESERVE_S, budget_s / 2)
    own_session = session is None
    session = session or requests.Session()
    from recall.parser import parse

    parsed = parse(text)
    try:
        out.stores = search_stores(kb, sources, terms, description=text, fits=lambda r: fits(parsed, r),
                                   session=session, deadline=deadline, clock=clock, max_pages=max_pages,
                                   names=described_names(before, terms, names.heads),
                                   as_judged=_judged)  # fmt: skip
    finally:
        if own_session:
            session.close()
    s = out.stores
    out.seconds.update(fetch=s.fetch_s, extract=s.extract_s, judge=s.judge_s, write=s.write_s)
    t0 = time.perf_counter()
    changed = out.stores.new_objects or out.stores.updated_objects
    out.after = Recaller.from_db(db).recall_parsed(parsed, **options) if changed else before
    out.seconds["recall"] += time.perf_counter() - t0
    out.seconds["total"] = clock.monotonic() - start
    _conclude(out)
    return out


def _conclude(out: LookupResult) -> None:
    """found and message, from what the stores did and the recall after."""
    stores, after = out.stores, out.after
    assert stores is not None and after is not None
    added = set(stores.new_objects) | set(stores.updated_objects)
    known = any(c.outcome == "known" for c in stores.candidates)
    best = after.best
    if not stores.answered:
        out.found = False
        out.message = f"{NOT_FOUND}: {stores.message}"
    elif not added and not known:
        out.found = False
        out.message = f"{NOT_FOUND} ({stores.message})"
    else:
        out.found = best is not None and not after.open_set
        out.message = f"{stores.message}; recalled {best.name if best else '-'} (confidence {after.confidence:.2f})"
