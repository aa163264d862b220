"""The records a recall returns: ranked :class:`Match` es and the :class:`RecallResult` around them."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from recall.fit import Fit
from recall.name_index import NameEvidence
from recall.openset import DescribedNoun
from recall.verdict import verdict

__all__ = ["Match", "RecallResult"]


@dataclass(frozen=True)
class Match:
    """One ranked catalog object: ``distance`` under the metric over the stated features, ``score`` the
    ranking score (the distance, minus the name bonus when the text names it), and the JP term of each
    stated feature (``contributions``: why this object)."""

    name: str
    distance: float
    score: float
    contributions: dict[str, float]
    matched_by_name: bool = False
    features: dict[str, Any] = field(default_factory=dict)
    #: The parts of ``score`` besides ``distance``: score = distance - name_part + vague_part.
    name_part: float = 0.0
    vague_part: float = 0.0
    kind: str | None = None

    def to_dict(self) -> dict[str, Any]:
        return {
            "name": self.name,
            "kind": self.kind,
            "distance": self.distance,
            "score": self.score,
            "name_part": self.name_part,
            "vague_part": self.vague_part,
            "matched_by_name": self.matched_by_name,
            "contributions": dict(self.contributions),
            "features": dict(self.features),
        }


@dataclass
class RecallResult:
    """What the robot gets: ranked matches, a calibrated confidence in [0, 1] that the first match is the
    described object, and ``open_set`` when even the best match is far from the description (it is still
    returned: the nearest object may still be graspable the same way)."""

    query: dict[str, Any]
    matches: list[Match]
    confidence: float
    open_set: bool
    metric: str
    features_only: bool
    named: list[str] = field(default_factory=list)
    closeness: float | None = None
    unknown_noun: str | None = None
    text: str | None = None
    parsed: dict[str, Any] | None = None
    #: The name evidence used (empty for features only); not part of the JSON.
    evidence: NameEvidence = field(default_factory=NameEvidence, repr=False)
    #: The description names a household noun the catalog does not have (``described``); the matches
    #: are then the physically closest objects, ``same_kind`` the closest of the noun's kind.
    not_in_catalog: bool = False
    described: DescribedNoun | None = None
    same_kind: list[Match] = field(default_factory=list)
    same_kind_as: str | None = None
    #: The vague words used as soft evidence (recall.vague), e.g. "small -> a_cm <= 9.8 cm".
    vague: list[str] = field(default_factory=list)
    #: The ranking's effective number of candidates (a confidence input; 1 = one clear first).
    competitors: float = 1.0
    #: The noun before the subject's head that the named best match's names lack ("salad" in "a salad
    #: plate" -> dinner plate): the name is then not trusted by the open-set rule.
    foreign_modifier: str | None = None
    #: Stated numeric features far from the best match's (``recall.openset.disagreeing_features``) and the
    #: refused values when none is left to compare (``recall.openset.nothing_compared``): not a close match.
    disagrees: tuple[str, ...] = ()
    unused: tuple[str, ...] = ()
    #: The best match's relative error per stated feature (:func:`recall.metrics.relative_errors`) and the
    #: judgement made on them (:func:`recall.fit.judge`: ``fit.score`` is the open-set score, above 1 when
    #: flagged; the same rule judges a store's product in a lookup).
    errors: dict[str, float] = field(default_factory=dict)
    fit: Fit | None = None
    #: A description in another language (:mod:`recall.translations`): the English reading the parser and
    #: the names read, and the words translated ((word, English) pairs); None and () for English text.
    read_as: str | None = None
    translated: tuple[tuple[str, str], ...] = ()
    #: The content words no table read, when they are most of them (:mod:`recall.openset_words`): the
    #: result is then no close match and its confidence low.
    unread: tuple[str, ...] = ()

    @property
    def best(self) -> Match | None:
        return self.matches[0] if self.matches else None

    def to_dict(self) -> dict[str, Any]:
        return {
            "text": self.text,
            "matches": [m.to_dict() for m in self.matches],
            "confidence": self.confidence,
            "open_set": self.open_set,
            "metric": self.metric,
            "features_only": self.features_only,
            "named": list(self.named),
            "closeness": self.closeness,
            "unknown_noun": self.unknown_noun,
            "not_in_catalog": self.not_in_catalog,
            "described": self.described.to_dict() if self.described else None,
            "same_kind": [m.to_dict() for m in self.same_kind],
            "same_kind_as": self.same_kind_as,
            "vague": list(self.vague),
            "competitors": self.competitors,
            "foreign_modifier": self.foreign_modifier,
            "disagrees": list(self.disagrees),
            "unused": list(self.unused),
            "read_as": self.read_as,
            "translated": [list(p) for p in self.translated],
            "unread": list(self.unread),
            "errors": dict(self.errors),
            "fit": self.fit.to_dict() if self.fit is not None else None,
            "verdict": verdict(self).to_dict(),
            "query": dict(self.query),
            "parsed": self.parsed,
        }
