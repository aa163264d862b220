"""The recall engine: from a description (or its features) to ranked catalog objects a robot can act on.

:class:`Recaller` ranks the objects of a :class:`~recall.snapshot.CatalogSnapshot` by the paper's Joint
Probability distance (or a baseline metric) over the stated features, and returns a
:class:`~recall.results.RecallResult`: ranked matches with their distance and per-feature contributions,
a calibrated confidence, and an open-set flag. The parts live in their own modules: names in the text
(:mod:`recall.name_index`, :mod:`recall.subject`), confidence (:mod:`recall.confidence`), the open-set
rule (:mod:`recall.openset`) and kinds (:mod:`recall.catalog_kinds`), vague words (:mod:`recall.vague`),
the candidate rows and their match records (:mod:`recall.shortlist`) and the result records
(:mod:`recall.results`); this module re-exports their public names. The rules are documented with their
numbers in ``recall/RECALL.md``.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from kb.errors import RecallError
from kb.features import CATEGORICAL_FEATURES, NUMERIC_FEATURES
from kb.kinds import ROOT, words_of
from recall.alternatives import alternatives, with_alternatives
from recall.catalog_kinds import KindIndex
from recall.confidence import (
    CONFIDENCE_COEF,
    JP_METRICS,
    MAX_LOOSE_FEATURES,
    MAX_MARGIN,
    NOT_IN_CATALOG_CONFIDENCE,
    capped_confidence,
    competitors_of,
    confidence_from_margin,
    confidence_of,
)
from recall.fit import Trust, disagree_factor, disagreeing_features, judge
from recall.geometry import ShapeGeometry, overrides
from recall.metrics import METRICS, FeatureQuery
from recall.name_index import HEAD_WEIGHT, NAME_WEIGHT, NameEvidence, NameIndex
from recall.names import GENERIC_NOUNS, name_core
from recall.openset import (
    OPEN_SET_NAMED_THRESHOLD,
    OPEN_SET_THRESHOLD,
    OPEN_SET_UNKNOWN_NOUN_THRESHOLD,
    DescribedNoun,
    describe,
    is_open_set,
    names_inside,
    nothing_compared,
)
from recall.openset_named import named_first
from recall.openset_verdict import row_closeness, row_fits, verdict
from recall.results import Match, RecallResult
from recall.search import select_top_k
from recall.shortlist import Shortlist, ranking_scores
from recall.snapshot import CatalogSnapshot, load_snapshot
from recall.subject import noun_phrase, subject_head, subject_phrase
from recall.submaterials import SubmaterialIndex, with_submaterial
from recall.unread import unknown_to_catalog
from recall.vague import SoftEvidence, soft_evidence

__all__ = [
    "CONFIDENCE_COEF",
    "confidence_from_margin",
    "confidence_of",
    "is_open_set",
    "DEFAULT_METRIC",
    "HEAD_WEIGHT",
    "NAME_WEIGHT",
    "NameEvidence",
    "GENERIC_NOUNS",
    "NOT_IN_CATALOG_CONFIDENCE",
    "OPEN_SET_NAMED_THRESHOLD",
    "OPEN_SET_THRESHOLD",
    "OPEN_SET_UNKNOWN_NOUN_THRESHOLD",
    "MAX_MARGIN",
    "Match",
    "NameIndex",
    "RecallResult",
    "Recaller",
    "name_core",
    "normalize_words",
    "resolve_metric",
    "subject_head",
    "subject_phrase",
]

#: The metric when none is given: the paper's JP for features only, JP in log units for the hybrid.
DEFAULT_METRIC = {True: "jp", False: "jplog"}
#: Lower-case word tokens, apostrophes dropped, hyphens split, plurals singular (:func:`kb.kinds.words_of`).
normalize_words = words_of


def resolve_metric(metric: str | None, features_only: bool) -> str:
    """``metric`` or, when None, the default for the mode (:data:`DEFAULT_METRIC`)."""
    return DEFAULT_METRIC[bool(features_only)] if metric is None else metric


class Recaller:
    """Recall objects from one catalog snapshot. Build with :meth:`from_db`, :meth:`from_csv`,
    :meth:`from_records` or from a snapshot. Thread-safe for reading."""

    def __init__(self, snapshot: CatalogSnapshot, name_tables: Any = None):
        """``name_tables``: the snapshot's name tables when already built (:mod:`recall.stored_index`)."""
        if len(snapshot) == 0:
            raise RecallError("the catalog is empty: import objects first (objrecall catalog import)")
        self.snapshot = snapshot
        from recall.stored_index import build_tables

        tables = build_tables(snapshot) if name_tables is None else name_tables
        self.names = NameIndex(snapshot.names, snapshot.aliases, tables=tables)
        self.kinds = KindIndex(snapshot.names, snapshot.aliases)
        self._geometry: ShapeGeometry | None = None
        self.shortlist = Shortlist(snapshot, self.kinds)
        #: Floors of a binned catalog (:mod:`recall.catalog_folder`): feature -> the value at or above which the
        #: catalog's value is a lower bound ("15 cm or more"); the closeness and the disagreement rule read
        #: them, and the ranking reads a stated value above one as the floor (``within_floors``).
        self.floors: dict[str, float] = {}
        #: Classes of a binned catalog (:mod:`recall.catalog_folder`, ``bins.csv``): feature -> (below, above),
        #: a stored value x stands for [x / below, x * above]; read like the floors, by the verdict only.
        self.bins: dict[str, tuple[float, float]] = {}
        from kb.features import CATEGORIES

        material = snapshot.cat_cols[CATEGORICAL_FEATURES.index("material")]
        other = CATEGORIES["material"].index("other")
        self._submaterials = SubmaterialIndex(snapshot.names, snapshot.aliases, material == other)

    @classmethod
    def from_db(cls, db: str | Path) -> Recaller:
        """A recaller over the catalog at ``db``, its index reloaded from beside the catalog when the
        catalog has not changed since it was stored (:func:`recall.stored_index.load_index`)."""
        from recall.stored_index import load_index

        path = Path(db)
        if not path.exists() or path.suffix.lower() == ".csv":
            return cls(load_snapshot(path))  # the snapshot's own error, or a catalog CSV
        index = load_index(path)
        return cls(index.snapshot, index.tables)

    @classmethod
    def from_csv(cls, path: str | Path) -> Recaller:
        return cls(load_snapshot(path))

    @classmethod
    def from_records(cls, records) -> Recaller:
        return cls(CatalogSnapshot.from_records(list(records)))

    # -- entry points
    def recall_text(
        self, text: str, *, top: int = 5, metric: str | None = None, features_only: bool = False
    ) -> RecallResult:
        """Parse ``text`` (recall.parser) and recall. Nonsense gives an empty, zero-confidence result. A
        description in another language is read in English first (:mod:`recall.translations`); one whose
        content words are mostly read by no table is no close match (:mod:`recall.openset_words`)."""
        from recall.openset_words import not_read, unread_words
        from recall.parser import parse
        from recall.translations import english_reading

        reading = english_reading(text, self.names.vocabulary) if isinstance(text, str) else None
        if reading is None or reading.language is None:
            result = self.recall_parsed(parse(text), top=top, metric=metric, features_only=features_only)
        else:
            result = self.recall_parsed(parse(reading.text), top=top, metric=metric, features_only=features_only)
            result.text, result.read_as, result.translated = text, reading.text, reading.translated
        unread = unread_words(reading.text, self.names.vocabulary) if reading is not None else ()
        return not_read(result, unread) if unread else result

    def recall_parsed(
        self, parsed: Any, *, top: int = 5, metric: str | None = None, features_only: bool = False
    ) -> RecallResult:
        """Recall from a parser result (``recall.parser.ParsedDescription``)."""
        parsed = unknown_to_catalog(parsed, self.names.vocabulary)  # "2 AA batteries": the catalog's word
        query = FeatureQuery.from_parsed(parsed)
        if not features_only:
            query = self._shape_from_geometry(query)
        text = parsed.text
        # numeric evidence is masked for name matching ("seven and quarter centimeters" names no coin)
        spans = [(ev.start, ev.end) for f, ev in parsed.features.items() if f in NUMERIC_FEATURES]
        material = parsed.values().get("material")
        names = NameEvidence() if features_only else self.names.find(text, spans, material)
        soft = noun = None
        subject: tuple[str, ...] = ()
        if not features_only:  # the paper's method uses the stated features only
            soft = with_submaterial(
                soft_evidence(text, parsed.values(), parsed.mass_hint, self.snapshot.num_cols),
                self._submaterial(parsed),
            )
            query, soft = with_alternatives(query, soft, alternatives(query, parsed), self.snapshot.cat_cols)
            subject = noun_phrase(text)
            noun = self.described(text)
            names = self._with_sorts(names, noun)
        result = self._recall(
            query, names, top=top, metric=metric, features_only=features_only, soft=soft, noun=noun,
            subject=subject, unused=nothing_compared(parsed.refused, bool(query.numeric)),
            refused=bool(nothing_compared(parsed.refused, False)),
        )  # fmt: skip
        result.text = text
        result.parsed = parsed.to_dict()
        result.parsed.pop("text", None)
        return result

    def recall_features(
        self,
        values: Mapping[str, Any],
        *,
        qualifiers: Mapping[str, str] | None = None,
        bounds: Mapping[str, tuple[float | None, float | None]] | None = None,
        text: str | None = None,
        top: int = 5,
        metric: str | None = None,
        features_only: bool = False,
    ) -> RecallResult:
        """Recall from feature values in catalog units (and, for the hybrid, the ``text`` to find names in)."""
        query = FeatureQuery.from_values(values, qualifiers, bounds)
        names = (
            NameEvidence()
            if features_only or not text
            else self.names.find(text, (), query.values().get("material"))
        )
        noun = self.described(text) if text and not features_only else None
        subject = noun_phrase(text) if text and not features_only else ()
        result = self._recall(
            query, names, top=top, metric=metric, features_only=features_only, noun=noun, subject=subject
        )
        result.text = text
        return result

    def _shape_from_geometry(self, query: FeatureQuery) -> FeatureQuery:
        """A stated shape word gives way to the class the three stated extents clearly have
        (:mod:`recall.geometry`): the geometry counts more than the word."""
        values = query.values()
        if "shape" not in values or not all(f in values for f in ("a_cm", "b_cm", "c_cm")):
            return query
        if self._geometry is None:
            self._geometry = ShapeGeometry.of_snapshot(self.snapshot)
        shape = self._geometry.classify(values["a_cm"], values["b_cm"], values["c_cm"])
        if shape is None or shape == values["shape"] or not overrides(shape, values["shape"]):
            return query
        cats = tuple((f, shape if f == "shape" else v) for f, v in query.categorical)
        return dataclasses.replace(query, categorical=cats)

    def _submaterial(self, parsed: Any) -> tuple[str, np.ndarray] | None:
        """The finer-material evidence of a stated ``other`` material (:mod:`recall.submaterials`)."""
        ev = parsed.features.get("material")
        if ev is None or ev.value != "other":
            return None
        return self._submaterials.penalty(ev.words or "")

    def _with_sorts(self, names: NameEvidence, noun: DescribedNoun | None) -> NameEvidence:
        """``names`` with the rows of the catalog head the described noun is a sort of (``noun.sort_of``:
        "a hacksaw" -> the saws), so that the ranking offers the objects the verdict holds it in the
        catalog as (:attr:`NameEvidence.sorts`); unchanged when it is no such sort or the text names them."""
        if noun is None or not noun.in_catalog or noun.sort_of is None:
            return names
        rows = self.names.heads.get(noun.sort_of) or set()
        rows = {r for r in rows if words_of(self.snapshot.names[r])[-1:] == [noun.sort_of]} - set(names.exact)
        if not rows:
            return names
        info = math.log(max(len(self.snapshot), 1) / len(rows))
        return dataclasses.replace(names, sorts=dict.fromkeys(sorted(rows), info))

    def described(self, text: str) -> DescribedNoun | None:
        """The noun the description names, and whether the catalog has it (:func:`recall.openset.describe`)."""
        return describe(text, self.names, self.kinds)

    # -- the ranking
    def _recall(
        self,
        query: FeatureQuery,
        names: NameEvidence,
        *,
        top: int,
        metric: str | None,
        features_only: bool,
        soft: SoftEvidence | None = None,
        noun: DescribedNoun | None = None,
        subject: tuple[str, ...] = (),
        unused: tuple[str, ...] = (),
        refused: bool = False,
    ) -> RecallResult:
        metric = _checked(metric, features_only, top)
        qdict = {
            "values": query.values(),
            "qualifiers": {c.feature: c.qualifier for c in query.numeric if c.qualifier != "about"},
        }
        base = dict(metric=metric, features_only=features_only, query=qdict)
        named = names.rows()
        if noun is not None and noun.kind == ROOT and len(query) == 0 and soft is None:
            noun = None  # an unseen noun and no feature ("qwerty uiop"): nothing to recall, not a foreign object
        not_in_catalog = noun is not None and not noun.in_catalog
        if len(query) == 0 and not named and soft is None:
            trust = Trust.FOREIGN if not_in_catalog else Trust.PLAIN
            fit = judge(None, {}, trust, (), noun.noun if not_in_catalog else None)
            return RecallResult(
                matches=[], confidence=0.0, open_set=not_in_catalog, not_in_catalog=not_in_catalog,
                described=noun, fit=fit, **base,
            )  # fmt: skip
        ranked = query.within_classes(self.bins) if self.bins else query  # a binned catalog's classes
        ranked = ranked.within_floors(self.floors) if self.floors else ranked  # open top bins: the floor
        rows, dist = self.shortlist.candidates(ranked, named, top, metric, soft)
        score, parts = ranking_scores(rows, dist, names, soft, metric)
        if names.rows() and not names_inside(noun, names.phrases):  # a named object that fits ranks first
            score, parts = named_first(rows, score, parts, names, lambda r, t: row_fits(self, r, query, soft, subject, t))
        competitors = competitors_of(score) if metric in JP_METRICS else 1.0
        rows, score = select_top_k(rows, score, min(len(rows), max(top, 2)))
        matches = self.shortlist.matches(rows, score, parts, ranked, metric, set(names.exact))
        best = int(rows[0])
        errors, closeness = row_closeness(self, best, query, soft)
        v = verdict(self, best, matches, names, noun, subject, not_in_catalog)
        not_in_catalog, unknown, modifier, trust = v.not_in_catalog, v.unknown, v.modifier, v.trust
        fit = judge(closeness, errors, trust, unused, noun.noun if not_in_catalog else None)
        open_set = not fit.close
        disagrees = disagreeing_features(errors, disagree_factor(trust))  # a stated value far off: the verdict says it
        margin = float(matches[1].score - matches[0].score) if len(matches) > 1 else MAX_MARGIN
        confidence = capped_confidence(
            margin, closeness, unknown is not None, metric, competitors, open_set, not_in_catalog, features_only,
            soft_only=len(query) <= MAX_LOOSE_FEATURES and not names.exact, refused=refused,
        )  # fmt: skip
        same_kind_as, same_kind = self.shortlist.same_kind(noun, ranked, metric) if not_in_catalog else (None, [])
        return RecallResult(
            matches=matches[:top],
            confidence=confidence,
            open_set=open_set,
            named=list(names.phrases),
            closeness=closeness,
            unknown_noun=unknown,
            evidence=names,
            not_in_catalog=not_in_catalog,
            described=noun,
            same_kind=same_kind,
            same_kind_as=same_kind_as,
            vague=list(soft.words) if soft is not None else [],
            competitors=competitors,
            foreign_modifier=modifier,
            disagrees=disagrees,
            unused=unused,
            errors=errors,
            fit=fit,
            **base,
        )


def _checked(metric: str | None, features_only: bool, top: int) -> str:
    """The metric to use (:func:`resolve_metric`), refusing an unknown one and a ``top`` below 1."""
    metric = resolve_metric(metric, features_only)
    if metric not in METRICS:
        raise RecallError(f"unknown metric {metric!r}; expected one of {', '.join(METRICS)}")
    if top < 1:
        raise RecallError(f"--top must be at least 1, not {top}")
    return metric
