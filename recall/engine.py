"""The recall engine: from a description (or its features) to ranked catalog objects a robot can act on.

:class:`Recaller` ranks the objects of a :class:`~recall.snapshot.CatalogSnapshot` by the paper's Joint
Probability distance (or a baseline metric) over the stated features, and returns a
:class:`RecallResult`: ranked :class:`Match` es with their distance and per-feature contributions, a
calibrated confidence, and an open-set flag. The rules (hybrid name evidence, confidence, open set) are
documented with their numbers in ``recall/RECALL.md``.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from kb.errors import RecallError
from kb.features import FEATURES, NUMERIC_FEATURES
from recall.metrics import METRICS, FeatureQuery, distances, feature_terms
from recall.search import score_rows, select_top_k, top_k
from recall.snapshot import CatalogSnapshot, load_snapshot

__all__ = [
    "CONFIDENCE_COEF",
    "HEAD_WEIGHT",
    "NAME_WEIGHT",
    "NameEvidence",
    "OPEN_SET_THRESHOLD",
    "Match",
    "NameIndex",
    "RecallResult",
    "Recaller",
    "normalize_words",
]

#: Hybrid: a name or alias in the text that names m of the catalog's N objects lowers each of their JP
#: distances by NAME_WEIGHT * ln(N / m) nats (multiplies the joint probability by (N / m)^NAME_WEIGHT);
#: a head noun only ("ball" -> every ball) by HEAD_WEIGHT * ln(N / m). Feature distance still ranks the
#: named candidates among themselves, and a named object whose features are far off can still lose.
NAME_WEIGHT = 0.6
HEAD_WEIGHT = 0.4
#: Confidence = 1 / (1 + exp(-(a + b * margin))), margin = second-best minus best ranking score (nats for
#: JP). Fitted by logistic regression on the development set (see RECALL.md and
#: ``python -m recall.evaluation --fit``).
CONFIDENCE_COEF: dict[str, tuple[float, float]] = {"jp": (-0.29, 2.46)}
#: Open set: the best match's mean JP term per stated feature above this (nats) means "not a close match".
OPEN_SET_THRESHOLD = 1.5


# --------------------------------------------------------------------------------------------- names
_WORD = re.compile(r"[a-z0-9]+")


def _singular(word: str) -> str:
    if len(word) <= 3 or word.endswith(("ss", "us", "is")):
        return word
    if word.endswith("ies") and len(word) > 4:
        return word[:-3] + "y"
    if word.endswith(("ches", "shes", "xes", "zes", "sses")):
        return word[:-2]
    if word.endswith("s"):
        return word[:-1]
    return word


def normalize_words(text: str) -> list[str]:
    """Lower-case word tokens, apostrophes dropped (rubik's -> rubiks), hyphens split, plurals singular."""
    text = text.lower().replace("'", "").replace("\u2019", "")
    return [_singular(w) for w in _WORD.findall(text)]


#: A name followed by one of these words only describes the object ("lemon-shaped", "pen-like").
_AFTER_COMPARISON = frozenset({"like", "shaped", "shape", "style", "type", "sized", "size", "looking"})
#: ... or preceded by these within two words ("like a pen", "the size of a tennis ball", "as big as").
_BEFORE_COMPARISON = frozenset({"like", "as", "than", "resemble", "resembling", "similar"})


def _comparison(words: list[str], start: int, end: int) -> bool:
    """Whether the name at words[start:end] is a comparison, not the object itself."""
    if end < len(words) and words[end] in _AFTER_COMPARISON:
        return True
    before = words[max(0, start - 3) : start]
    if any(w in _BEFORE_COMPARISON for w in before):
        return True
    return (
        len(before) >= 2 and before[-2:] in (["size", "of"], ["size", "a"]) or before[-3:-1] == ["size", "of"]
    )


def _head(words: tuple[str, ...]) -> str:
    """The head noun of a name: the word before "of" ("bottle of water"), else the last word."""
    if "of" in words[1:]:
        return words[words.index("of", 1) - 1]
    return words[-1]


@dataclass(frozen=True)
class NameEvidence:
    """Catalog rows a description names and the information of the naming, in nats: a phrase that names
    m of the N catalog objects carries ln(N / m). ``exact``: by a whole name or alias (the longest
    matches); ``head``: by the head noun of a name or alias only ("a plastic ball" -> every ball,
    "spoon" -> teaspoon)."""

    exact: dict[int, float] = field(default_factory=dict)
    head: dict[int, float] = field(default_factory=dict)
    phrases: tuple[str, ...] = ()
    heads: tuple[str, ...] = ()

    def rows(self) -> list[int]:
        return sorted(set(self.exact) | set(self.head))

    def bonus(self, row: int) -> float:
        """Nats subtracted from the row's JP distance (see RECALL.md)."""
        return max(NAME_WEIGHT * self.exact.get(row, 0.0), HEAD_WEIGHT * self.head.get(row, 0.0))


class NameIndex:
    """Catalog names and aliases as word n-grams and head nouns, for finding the objects a description
    names."""

    #: Shortest head noun matched as the end of a compound ("spoon" in "teaspoon").
    MIN_SUFFIX = 4

    def __init__(self, names: Sequence[str], aliases: Sequence[Sequence[str]]):
        from recall.lexicon import MATERIAL_WORDS

        self.phrases: dict[tuple[str, ...], set[int]] = {}
        self.heads: dict[str, set[int]] = {}
        # (head, row) -> materials its names state ("wood cylinder" -> wood); None: some name states none
        self.head_materials: dict[tuple[str, int], set[str] | None] = {}
        for row, (name, alias) in enumerate(zip(names, aliases, strict=True)):
            for phrase in (name, *alias):
                words = tuple(normalize_words(phrase))
                if words:
                    self.phrases.setdefault(words, set()).add(row)
                    head = _head(words)
                    stated = {MATERIAL_WORDS[w] for w in words if w in MATERIAL_WORDS and w != head}
                    for key in (head, *(head[cut:] for cut in range(1, len(head) - self.MIN_SUFFIX + 1))):
                        self.heads.setdefault(key, set()).add(row)
                        known = self.head_materials.get((key, row), set())
                        self.head_materials[(key, row)] = (
                            None if known is None or not stated else known | stated
                        )
        # material words name what a thing is made of, not the thing ("made of glass")
        self.not_heads = frozenset(_singular(w) for w in MATERIAL_WORDS if " " not in w)
        self.longest = max((len(p) for p in self.phrases), default=0)
        self.size = len(names)

    def find(
        self, text: str, skip_spans: Sequence[tuple[int, int]] = (), material: str | None = None
    ) -> NameEvidence:
        """The rows named in ``text``.

        Characters in ``skip_spans`` (the parser's numeric evidence, so "seven and quarter centimeters"
        never names the US quarter) are ignored, and so are comparisons ("lemon-shaped", "like a pen",
        "the size of a tennis ball"). Exact matches inside a longer match are dropped, then the longest
        remaining phrases win. A head noun does not name an object whose names all state another
        material than the description's ``material`` ("a metal cylinder" is no "wood cylinder").
        """
        chars = list(text)
        for start, end in skip_spans:
            for i in range(max(0, start), min(len(chars), end)):
                chars[i] = " "
        words = normalize_words("".join(chars))
        found: list[tuple[int, int, tuple[str, ...]]] = []
        for n in range(min(self.longest, len(words)), 0, -1):
            for i in range(len(words) - n + 1):
                gram = tuple(words[i : i + n])
                if gram not in self.phrases or any(s <= i and i + n <= e for s, e, _ in found):
                    continue
                if _comparison(words, i, i + n):
                    continue
                found.append((i, i + n, gram))
        n = max(self.size, 1)
        exact: dict[int, float] = {}
        phrases: list[str] = []
        if found:
            best = max(e - s for s, e, _ in found)
            for s, e, gram in found:
                if e - s == best:
                    rows = self.phrases[gram]
                    for row in rows:
                        exact[row] = max(exact.get(row, 0.0), math.log(n / len(rows)))
                    phrases.append(" ".join(gram))
        head: dict[int, float] = {}
        heads: list[str] = []
        for i, word in enumerate(words):
            if word in self.heads and word not in self.not_heads and not _comparison(words, i, i + 1):
                rows = self.heads[word]
                for row in rows:
                    implied = self.head_materials.get((word, row))
                    if material is not None and implied and material not in implied:
                        continue
                    head[row] = max(head.get(row, 0.0), math.log(n / len(rows)))
                heads.append(word)
        return NameEvidence(exact, head, tuple(dict.fromkeys(phrases)), tuple(dict.fromkeys(heads)))


# ------------------------------------------------------------------------------------------- results
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

    def to_dict(self) -> dict[str, Any]:
        return {
            "name": self.name,
            "distance": self.distance,
            "score": self.score,
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
    text: str | None = None
    parsed: dict[str, Any] | None = None

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
            "query": dict(self.query),
            "parsed": self.parsed,
        }


def confidence_from_margin(margin: float, metric: str = "jp") -> float:
    """The calibrated probability that the first match is right, from the ranking-score margin."""
    a, b = CONFIDENCE_COEF.get(metric, CONFIDENCE_COEF["jp"])
    if metric != "jp":  # the baselines' distances are on other scales: rescale the margin to nats
        margin = math.log1p(max(margin, 0.0))
    z = a + b * margin
    return float(1.0 / (1.0 + math.exp(-max(min(z, 50.0), -50.0))))


# ------------------------------------------------------------------------------------------ recaller
class Recaller:
    """Recall objects from one catalog snapshot. Build with :meth:`from_db`, :meth:`from_csv`,
    :meth:`from_records` or from a snapshot. Thread-safe for reading."""

    def __init__(self, snapshot: CatalogSnapshot):
        if len(snapshot) == 0:
            raise RecallError("the catalog is empty: import objects first (objrecall catalog import)")
        self.snapshot = snapshot
        self.names = NameIndex(snapshot.names, snapshot.aliases)
        self._kdtrees: dict = {}

    @classmethod
    def from_db(cls, db: str | Path) -> Recaller:
        return cls(load_snapshot(db))

    @classmethod
    def from_csv(cls, path: str | Path) -> Recaller:
        return cls(load_snapshot(path))

    @classmethod
    def from_records(cls, records) -> Recaller:
        return cls(CatalogSnapshot.from_records(list(records)))

    # -- entry points
    def recall_text(
        self, text: str, *, top: int = 5, metric: str = "jp", features_only: bool = False
    ) -> RecallResult:
        """Parse ``text`` (recall.parser) and recall. Nonsense gives an empty, zero-confidence result."""
        from recall.parser import parse

        return self.recall_parsed(parse(text), top=top, metric=metric, features_only=features_only)

    def recall_parsed(
        self, parsed: Any, *, top: int = 5, metric: str = "jp", features_only: bool = False
    ) -> RecallResult:
        """Recall from a parser result (``recall.parser.ParsedDescription``)."""
        query = FeatureQuery.from_parsed(parsed)
        text = parsed.text
        # numeric evidence is masked for name matching ("seven and quarter centimeters" names no coin)
        spans = [(ev.start, ev.end) for f, ev in parsed.features.items() if f in NUMERIC_FEATURES]
        material = parsed.values().get("material")
        names = NameEvidence() if features_only else self.names.find(text, spans, material)
        result = self._recall(query, names, top=top, metric=metric, features_only=features_only)
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
        metric: str = "jp",
        features_only: bool = False,
    ) -> RecallResult:
        """Recall from feature values in catalog units (and, for the hybrid, the ``text`` to find names in)."""
        query = FeatureQuery.from_values(values, qualifiers, bounds)
        names = (
            NameEvidence()
            if features_only or not text
            else self.names.find(text, (), query.values().get("material"))
        )
        result = self._recall(query, names, top=top, metric=metric, features_only=features_only)
        result.text = text
        return result

    # -- the ranking
    def _distances_of(self, query: FeatureQuery, rows: np.ndarray, metric: str) -> np.ndarray:
        if metric == "jp":
            return score_rows(self.snapshot, query, rows)
        return distances(metric, self.snapshot.matrix, query, kdtree_cache=self._kdtrees)[rows]

    def _recall(
        self,
        query: FeatureQuery,
        names: NameEvidence,
        *,
        top: int,
        metric: str,
        features_only: bool,
    ) -> RecallResult:
        if metric not in METRICS:
            raise RecallError(f"unknown metric {metric!r}; expected one of {', '.join(METRICS)}")
        if top < 1:
            raise RecallError(f"--top must be at least 1, not {top}")
        snap = self.snapshot
        qdict = {
            "values": query.values(),
            "qualifiers": {c.feature: c.qualifier for c in query.numeric if c.qualifier != "about"},
        }
        base = dict(metric=metric, features_only=features_only, query=qdict)
        named = names.rows()
        if len(query) == 0 and not named:
            return RecallResult(matches=[], confidence=0.0, open_set=False, **base)
        want = min(len(snap), top + 1 + len(named))
        rows, dist = top_k(snap, query, want, metric=metric, kdtree_cache=self._kdtrees)
        score = dist.copy()
        if named:
            extra = np.setdiff1d(np.asarray(named, dtype=np.int64), rows)
            if len(extra):
                rows = np.concatenate((rows, extra))
                dist = np.concatenate((dist, self._distances_of(query, extra, metric)))
            bonus = np.array([names.bonus(int(r)) for r in rows])
            if metric == "jp":
                score = dist - bonus
            else:  # other metrics have no probabilistic scale: named objects rank first, by their evidence
                score = dist - (dist.max() + 1.0) * bonus
        order_dist = {int(r): float(d) for r, d in zip(rows, dist, strict=True)}
        rows, score = select_top_k(rows, score, min(len(rows), max(top, 2)))
        named_set = set(names.exact)
        terms = feature_terms(snap.num[rows], snap.cat[rows], query)
        matches = []
        for i, row in enumerate(rows):
            row = int(row)
            rec = snap.record(row)
            matches.append(
                Match(
                    name=snap.names[row],
                    distance=order_dist[row],
                    score=float(score[i]),
                    contributions={f: float(terms[f][i]) for f in query.stated},
                    matched_by_name=row in named_set,
                    features={f: getattr(rec, f) for f in FEATURES},
                )
            )
        margin = float(matches[1].score - matches[0].score) if len(matches) > 1 else 10.0
        confidence = confidence_from_margin(margin, metric)
        best = matches[0]
        closeness = float(np.mean(list(best.contributions.values()))) if best.contributions else None
        open_set = bool(closeness is not None and closeness > OPEN_SET_THRESHOLD and not best.matched_by_name)
        if open_set:
            confidence = min(confidence, 0.5)
        return RecallResult(
            matches=matches[:top],
            confidence=confidence,
            open_set=open_set,
            named=list(names.phrases),
            closeness=closeness,
            **base,
        )
