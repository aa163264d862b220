"""The recall engine: from a description (or its features) to ranked catalog objects a robot can act on.

:class:`Recaller` ranks the objects of a :class:`~recall.snapshot.CatalogSnapshot` by the paper's Joint
Probability distance (or a baseline metric) over the stated features, and returns a
:class:`RecallResult`: ranked :class:`Match` es with their distance and per-feature contributions, a
calibrated confidence, and an open-set flag. The rules (hybrid name evidence, confidence, open set) are
documented with their numbers in ``recall/RECALL.md``.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from kb.errors import RecallError
from kb.features import FEATURES, NUMERIC_FEATURES
from kb.kinds import singular, words_of
from recall.geometry import ShapeGeometry, overrides
from recall.metrics import METRICS, FeatureQuery, distances, feature_terms, relative_errors
from recall.names import GENERIC_NOUNS, MIN_SUFFIX, name_core
from recall.openset import DescribedNoun, KindIndex, described_noun
from recall.search import score_rows, select_top_k, top_k
from recall.snapshot import CatalogSnapshot, load_snapshot
from recall.vague import SoftEvidence, soft_evidence

__all__ = [
    "CONFIDENCE_COEF",
    "confidence_of",
    "is_open_set",
    "DEFAULT_METRIC",
    "HEAD_WEIGHT",
    "NAME_WEIGHT",
    "NameEvidence",
    "GENERIC_NOUNS",
    "OPEN_SET_NAMED_THRESHOLD",
    "OPEN_SET_THRESHOLD",
    "OPEN_SET_UNKNOWN_NOUN_THRESHOLD",
    "Match",
    "NameIndex",
    "RecallResult",
    "Recaller",
    "name_core",
    "normalize_words",
    "resolve_metric",
]

#: Hybrid: a name or alias in the text that names m of the catalog's N objects lowers each of their JP
#: distances by NAME_WEIGHT * ln(N / m) nats (multiplies the joint probability by (N / m)^NAME_WEIGHT);
#: a head noun only ("ball" -> every ball) by HEAD_WEIGHT * ln(N / m). Feature distance still ranks the
#: named candidates among themselves, and a named object whose features are far off can still lose.
NAME_WEIGHT = 0.6
HEAD_WEIGHT = 0.4
#: Confidence = 1 / (1 + exp(-(a + b * margin + c * closeness + d * unknown_noun + e * ln competitors))):
#: margin = second-best minus best ranking score (nats, capped at MAX_MARGIN), closeness the best match's
#: mean relative error, unknown_noun 1 when the subject is a noun the catalog does not know, competitors
#: the ranking's effective number of candidates (1 / its softmax posterior of the first). Fitted by logistic regression on
#: the development set and its open set (``python -m recall.evaluation --fit``; RECALL.md).
CONFIDENCE_COEF: tuple[float, float, float, float, float] = (3.69, 0.39, -10.54, -1.73, -1.61)
MAX_MARGIN = 10.0
#: Candidates always scored, whatever ``top``, so that ``competitors`` (and the confidence) does not
#: depend on how many matches are shown.
COMPETITOR_POOL = 16
#: An open-set result's confidence is at most this.
OPEN_SET_CONFIDENCE_CAP = 0.5
#: ... and a description naming a noun the catalog does not have at most this (its first match is the
#: physically closest object, never the described one; measured in RECALL.md).
NOT_IN_CATALOG_CONFIDENCE = 0.05
#: Open set: the best match's closeness (mean relative error over the stated features, see
#: :func:`recall.metrics.relative_errors`) above this means "not a close match" ...
OPEN_SET_THRESHOLD = 0.30
#: ... above this when the description names the match by a whole name or alias (a name is evidence) ...
OPEN_SET_NAMED_THRESHOLD = 0.45
#: ... and above this when the subject of the description is a noun the catalog does not know ("an
#: orange", "a watermelon"): an unknown noun alone is not enough (synonyms), with a loose match it is.
OPEN_SET_UNKNOWN_NOUN_THRESHOLD = 0.15
#: Metrics in nats (a name bonus can be subtracted; the margin is a log-likelihood ratio).
_JP_METRICS = ("jp", "jplog")
#: The metric when none is given: the paper's JP for features only, JP in log units for the hybrid.
DEFAULT_METRIC = {True: "jp", False: "jplog"}


def resolve_metric(metric: str | None, features_only: bool) -> str:
    """``metric`` or, when None, the default for the mode (:data:`DEFAULT_METRIC`)."""
    return DEFAULT_METRIC[bool(features_only)] if metric is None else metric


# --------------------------------------------------------------------------------------------- names
_WORD = re.compile(r"[a-z0-9]+")


_singular = singular
#: Lower-case word tokens, apostrophes dropped, hyphens split, plurals singular (:func:`kb.kinds.words_of`).
normalize_words = words_of




#: A name followed by one of these words only describes the object ("lemon-shaped", "pen-like").
#: ("die-cast": made in a die, not a die).
_AFTER_COMPARISON = frozenset(
    {"like", "shaped", "shape", "style", "type", "sized", "size", "looking", "cast"}
)
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


#: Words that end the subject noun phrase: function words, pronouns and the commonest verbs of a
#: description ("a fuzzy ball *with* ...", "an orange *of* 7 cm", "a cork *from* a bottle").
_PHRASE_ENDS = frozenset(
    "is are was were be been being with without of from for that which who about around roughly approximately "
    "nearly almost over under weighs weigh weighing weighed measuring measures measure measured made covered "
    "in on at into onto inside and or but has have had it its i im me my we our you your he she they their "
    "this these those there here whose when while if so to by like maybe probably "
    # irregular participles ("a wood piece cut at a slant")
    "cut worn bent broken torn split built found bought kept held sewn woven spun".split()
)
_PRONOUNS = frozenset({"i", "we", "you", "he", "she", "they"})
#: Words skipped inside the subject phrase (determiners, vague size words).
_PHRASE_SKIP = frozenset(
    "a an the some one just very really little small big large tiny huge old new".split()
)


def subject_head(text: str) -> str | None:
    """The last word of :func:`subject_phrase`, or None."""
    phrase = subject_phrase(text)
    return phrase[-1] if phrase else None


def subject_phrase(text: str) -> tuple[str, ...]:
    """The words of the description's subject noun phrase, singular; the last is its head noun: the first
    noun phrase of the first sentence (words up to a comma, a number or a word of :data:`_PHRASE_ENDS`; determiners and vague size
    words skipped), singular. "A plush dinosaur toy, 35 cm" -> toy; "An orange of 7 cm" -> orange;
    "My daughter's teddy bear" -> bear. No part-of-speech tagger: a heuristic, used only as evidence."""
    low = text.lower().replace("\u2019", "'")
    low = re.sub(r"\b(it|that|there|what|he|she)'s\b", r"\1 is", low).replace("'s", "").replace("'", "")
    sentence = re.split(r"[.!?;:\n]", low, maxsplit=1)[0]
    for chunk in re.split(r"[,()\[\]\d\"/&+*=-]", sentence):
        phrase: list[str] = []
        previous = ""
        for word in _WORD.findall(chunk):
            if word in _PHRASE_ENDS:
                if phrase:
                    break
            elif previous in _PRONOUNS:  # "i found this ...": the word after a pronoun is its verb
                pass
            elif word not in _PHRASE_SKIP:
                phrase.append(word)
            previous = word
        if phrase:
            return tuple(_singular(w) for w in phrase)
    return ()


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
    #: The subject's head noun when the catalog does not know it (:meth:`NameIndex.unknown_noun`).
    unknown_noun: str | None = None

    def rows(self) -> list[int]:
        return sorted(set(self.exact) | set(self.head))

    def bonus(self, row: int) -> float:
        """Nats subtracted from the row's JP distance (see RECALL.md)."""
        return max(NAME_WEIGHT * self.exact.get(row, 0.0), HEAD_WEIGHT * self.head.get(row, 0.0))


class NameIndex:
    """Catalog names and aliases as word n-grams and head nouns, for finding the objects a description
    names."""

    #: Shortest head noun matched as the end of a compound ("spoon" in "teaspoon").
    MIN_SUFFIX = MIN_SUFFIX

    def __init__(
        self,
        names: Sequence[str],
        aliases: Sequence[Sequence[str]],
        materials: Sequence[str | None] | None = None,
        tables: Any = None,
    ):
        from recall.lexicon import MATERIAL_WORDS
        from recall.names import name_tables

        # built column-wise (recall.names; or read back by recall.stored_index): phrases (words and core
        # of every name and alias) -> rows; generic names ("wood piece", "wooden block": only material
        # words and generic nouns) -> their material, describing any object of it (rows by material);
        # head nouns and their suffixes -> rows, and (head, row) -> the materials its names state
        # ("wood cylinder" -> wood; None: some name states none)
        if tables is None:
            tables = name_tables(names, aliases, materials, self.MIN_SUFFIX)
        self.phrases = tables.phrases
        self.generic = tables.generic
        self.by_material = tables.by_material
        self.heads = tables.heads
        self.head_materials = tables.head_materials
        # material words name what a thing is made of, not the thing ("made of glass")
        self.not_heads = frozenset(_singular(w) for w in MATERIAL_WORDS if " " not in w)
        self.vocabulary = tables.vocabulary
        self.longest = tables.longest
        self.size = len(names)

    def unknown_noun(self, text: str) -> str | None:
        """The head noun of the description's subject (:func:`subject_head`) when the catalog does not know
        it: in no name or alias, not a feature word of the parser's lexicon (materials, shapes, units,
        ...; a colour word counts as a noun here: "an orange"), not a generic noun (:data:`GENERIC_NOUNS`)."""
        phrase = subject_phrase(text)
        head = phrase[-1] if phrase else None
        if (
            len(phrase) > 1
            and phrase[-2] in self.heads
            and phrase[-2] not in GENERIC_NOUNS
            and phrase[-2] not in self.not_heads
        ):
            return None  # a compound on a known noun: "remote control" (tv remote), "bottle cap"
        if head is None or head in self.vocabulary or head in GENERIC_NOUNS or _PARTICIPLE.search(head):
            return None
        if head in _feature_words():
            return None
        return head

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
        head: dict[int, float] = {}
        if found:
            best = max(e - s for s, e, _ in found)
            for s, e, gram in found:
                if e - s == best and gram in self.generic:
                    # "a wood piece" names no one object: weak evidence for every object of its material
                    rows = self.phrases[gram] | self.by_material.get(self.generic[gram], set())
                    for row in rows:
                        head[row] = max(head.get(row, 0.0), math.log(n / len(rows)))
                elif e - s == best:
                    rows = self.phrases[gram]
                    for row in rows:
                        exact[row] = max(exact.get(row, 0.0), math.log(n / len(rows)))
                    phrases.append(" ".join(gram))
        heads: list[str] = []
        for i, word in enumerate(words):
            if word in self.heads and word not in self.not_heads and not _comparison(words, i, i + 1):
                if word in _adjective_feature_words() and (word,) not in self.phrases:
                    continue  # a feature word ("light", "heavy") is no head noun ("tea light")
                rows = self.heads[word]
                for row in rows:
                    implied = self.head_materials.get((word, row))
                    if material is not None and implied and material not in implied:
                        continue
                    head[row] = max(head.get(row, 0.0), math.log(n / len(rows)))
                heads.append(word)
        return NameEvidence(
            exact,
            head,
            tuple(dict.fromkeys(phrases)),
            tuple(dict.fromkeys(heads)),
            self.unknown_noun(text),
        )


@functools.cache
def _feature_words() -> frozenset[str]:
    """Single words of the parser's lexicon that state a feature, a unit, a number or a hedge. Colour
    words and the object nouns among the shape words ("orange", "candle", "vase") are left out: as the
    head of the subject they name the object; of the shape words only adjectives ("round", "cylindrical",
    "ball-shaped") are kept."""
    from recall import lexicon as lx

    words: set[str] = set()
    tables = (
        lx.MATERIAL_WORDS, lx.RIGIDITY_WORDS, lx.TEXTURE_WORDS, lx.FRAGILITY_WORDS, lx.MASS_HINT_WORDS,
        lx.DIMENSION_WORDS, lx.NUMBER_WORDS, lx.MAGNITUDE_WORDS, lx.FRACTION_WORDS, lx.HEDGES,
        lx.LENGTH_UNITS, lx.MASS_UNITS, lx.VOLUME_UNITS, lx.MEDIUM_WORDS, lx.DIMENSION_NOUNS, lx.FILL_WORDS,
        lx.CAPACITY_WORDS, lx.NEGATIONS,
    )  # fmt: skip
    for table in tables:
        for phrase in table:
            words.update(normalize_words(phrase))
    shape_words = set(lx.SHAPE_WORDS) | lx.SPHERE_WORDS | lx.CUBE_WORDS | lx.FLAT_WORDS | lx.ROUND_WORDS
    for word in shape_words | lx.CYLINDER_WORDS | lx.DISC_WORDS:
        if _ADJECTIVE.search(word) or word in _SHAPE_ADJECTIVES:
            words.update(normalize_words(word))
    return frozenset(words)


@functools.cache
def _adjective_feature_words() -> frozenset[str]:
    """Single words that state a mass hint, texture, rigidity or fragility ("light", "soft"): adjectives,
    never a head noun, although a catalog name may end in one ("tea light")."""
    from recall import lexicon as lx

    tables = (lx.MASS_HINT_WORDS, lx.TEXTURE_WORDS, lx.RIGIDITY_WORDS, lx.FRAGILITY_WORDS)
    return frozenset(w for table in tables for w in table if " " not in w)


#: Participles and adjectives that end a phrase ("full", "filled", "folded", "useful"): never a head.
_PARTICIPLE = re.compile(r"^(full|play|fake|toy)$|..(ed|ful|ous|able|ible)$")
_ADJECTIVE = re.compile(r"(al|ic|ed|y|ish|ar|shaped|like)$")
_SHAPE_ADJECTIVES = frozenset(
    {"flat", "round", "long", "thin", "slim", "slender", "compact", "oval", "squat", "floppy"}
)


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
            "query": dict(self.query),
            "parsed": self.parsed,
        }


def is_open_set(closeness: float | None, named: bool, unknown_noun: str | None) -> bool:
    """The open-set rule (RECALL.md): the best match is not a close match when its closeness (mean
    relative error) exceeds :data:`OPEN_SET_THRESHOLD`, :data:`OPEN_SET_NAMED_THRESHOLD` when the text
    names it exactly, or :data:`OPEN_SET_UNKNOWN_NOUN_THRESHOLD` when the subject is an unknown noun."""
    if closeness is None:
        return False
    if named:
        return closeness > OPEN_SET_NAMED_THRESHOLD
    if unknown_noun is not None:
        return closeness > OPEN_SET_UNKNOWN_NOUN_THRESHOLD
    return closeness > OPEN_SET_THRESHOLD


def confidence_of(
    margin: float,
    closeness: float | None,
    unknown_noun: bool,
    metric: str = "jp",
    competitors: float = 1.0,
) -> float:
    """The calibrated probability that the first match is the described object: a logistic model of the
    ranking-score margin (nats, capped at :data:`MAX_MARGIN`), the closeness, whether the subject is an
    unknown noun and ln(``competitors``), the ranking's effective number of candidates (1 / its own
    posterior of the first: k near-tied objects give about k; :data:`CONFIDENCE_COEF`, fitted on the
    development sets; see RECALL.md)."""
    a, b, c, d, e = CONFIDENCE_COEF
    if metric not in _JP_METRICS:  # the baselines' distances are on other scales: rescale the margin to nats
        margin = math.log1p(max(margin, 0.0))
    margin = min(max(margin, 0.0), MAX_MARGIN)
    z = a + b * margin + c * (closeness or 0.0) + d * float(unknown_noun) + e * math.log(max(competitors, 1.0))
    # never above the two-candidate posterior of the ranking itself, e^m / (1 + e^m): a tie is at most 0.5
    return float(min(_sigmoid(z), _sigmoid(margin)))


def _sigmoid(z: float) -> float:
    return 1.0 / (1.0 + math.exp(-max(min(z, 50.0), -50.0)))


def confidence_from_margin(margin: float, metric: str = "jp") -> float:
    """The confidence of a result with this margin, a perfect closeness and a known subject."""
    return confidence_of(margin, 0.0, False, metric)


# ------------------------------------------------------------------------------------------ recaller
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
        self._kdtrees: dict = {}

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
        """Parse ``text`` (recall.parser) and recall. Nonsense gives an empty, zero-confidence result."""
        from recall.parser import parse

        return self.recall_parsed(parse(text), top=top, metric=metric, features_only=features_only)

    def recall_parsed(
        self, parsed: Any, *, top: int = 5, metric: str | None = None, features_only: bool = False
    ) -> RecallResult:
        """Recall from a parser result (``recall.parser.ParsedDescription``)."""
        query = FeatureQuery.from_parsed(parsed)
        if not features_only:
            query = self._shape_from_geometry(query)
        text = parsed.text
        # numeric evidence is masked for name matching ("seven and quarter centimeters" names no coin)
        spans = [(ev.start, ev.end) for f, ev in parsed.features.items() if f in NUMERIC_FEATURES]
        material = parsed.values().get("material")
        names = NameEvidence() if features_only else self.names.find(text, spans, material)
        soft = noun = None
        if not features_only:  # the paper's method uses the stated features only
            soft = soft_evidence(text, parsed.values(), parsed.mass_hint, self.snapshot.num_cols)
            noun = self.described(text)
        result = self._recall(
            query, names, top=top, metric=metric, features_only=features_only, soft=soft, noun=noun
        )
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
        result = self._recall(query, names, top=top, metric=metric, features_only=features_only, noun=noun)
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

    def described(self, text: str) -> DescribedNoun | None:
        """The lexicon noun the description's subject names, and whether the catalog has it."""
        idx = self.names
        subject = subject_phrase(text)
        after_of: tuple[str, ...] = ()
        if subject:  # "a bar of soap", "a pair of scissors": the noun after "of"
            m = re.search(rf"\b{re.escape(subject[-1])}s?\s+of\s+(.*)", text.lower())
            after_of = subject_phrase(m.group(1)) if m else ()
        return described_noun(subject, idx.phrases, idx.heads, idx.vocabulary, GENERIC_NOUNS, after_of)

    # -- the ranking
    def _distances_of(self, query: FeatureQuery, rows: np.ndarray, metric: str) -> np.ndarray:
        if metric == "jp":
            return score_rows(self.snapshot, query, rows)
        if metric == "jplog":
            return score_rows(self.snapshot.log_scaled, query.log_scaled(), rows)
        return distances(metric, self.snapshot.matrix, query, kdtree_cache=self._kdtrees)[rows]

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
    ) -> RecallResult:
        metric = resolve_metric(metric, features_only)
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
        not_in_catalog = noun is not None and not noun.in_catalog
        if len(query) == 0 and not named and soft is None:
            return RecallResult(
                matches=[], confidence=0.0, open_set=not_in_catalog, not_in_catalog=not_in_catalog,
                described=noun, **base,
            )  # fmt: skip
        rows, dist = self._candidates(query, named, top, metric, soft is not None)
        bonus = np.array([names.bonus(int(r)) for r in rows]) if named else np.zeros(len(rows))
        vague = soft.penalty[rows] if soft is not None else np.zeros(len(rows))
        if metric in _JP_METRICS:
            score = dist - bonus + vague
        else:  # other metrics have no probabilistic scale: named objects rank first, by their evidence
            score = dist - (dist.max() + 1.0) * bonus + vague
        competitors = _competitors(score) if metric in _JP_METRICS else 1.0
        order = {int(r): (float(d), float(b), float(v)) for r, d, b, v in zip(rows, dist, bonus, vague, strict=True)}
        rows, score = select_top_k(rows, score, min(len(rows), max(top, 2)))
        matches = self._matches(rows, score, order, query, metric, set(names.exact))
        margin = float(matches[1].score - matches[0].score) if len(matches) > 1 else MAX_MARGIN
        best = int(rows[0])
        errors = relative_errors(snap.num_rows(best), snap.cat_rows(best), query)
        closeness = float(np.mean(list(errors.values()))) if errors else None
        not_in_catalog = not_in_catalog and not matches[0].matched_by_name
        open_set = not_in_catalog or is_open_set(closeness, matches[0].matched_by_name, names.unknown_noun)
        confidence = confidence_of(margin, closeness, names.unknown_noun is not None, metric, competitors)
        if open_set:
            confidence = min(confidence, OPEN_SET_CONFIDENCE_CAP)
        if not_in_catalog:
            confidence = min(confidence, NOT_IN_CATALOG_CONFIDENCE)
        same_kind_as, same_kind = self._same_kind(noun, query, metric) if not_in_catalog else (None, [])
        return RecallResult(
            matches=matches[:top],
            confidence=confidence,
            open_set=open_set,
            named=list(names.phrases),
            closeness=closeness,
            unknown_noun=names.unknown_noun,
            evidence=names,
            not_in_catalog=not_in_catalog,
            described=noun,
            same_kind=same_kind,
            same_kind_as=same_kind_as,
            vague=list(soft.words) if soft is not None else [],
            competitors=competitors,
            **base,
        )

    def _candidates(
        self, query: FeatureQuery, named: list[int], top: int, metric: str, every_row: bool
    ) -> tuple[np.ndarray, np.ndarray]:
        """Rows that can rank in the first ``top`` and their distances: the pruned top-k plus the named
        rows; every row when soft evidence can reorder them (vague words: one scan)."""
        snap = self.snapshot
        if every_row:
            rows = np.arange(len(snap), dtype=np.int64)
            return rows, self._distances_of(query, rows, metric) if len(query) else np.zeros(len(rows))
        want = min(len(snap), max(top + 1, COMPETITOR_POOL) + len(named))
        rows, dist = top_k(snap, query, want, metric=metric, kdtree_cache=self._kdtrees)
        extra = np.setdiff1d(np.asarray(named, dtype=np.int64), rows)
        if len(extra):
            rows = np.concatenate((rows, extra))
            dist = np.concatenate((dist, self._distances_of(query, extra, metric)))
        return rows, dist

    def _matches(
        self,
        rows: np.ndarray,
        score: np.ndarray,
        parts: Mapping[int, tuple[float, float, float]],
        query: FeatureQuery,
        metric: str,
        named_exact: set[int],
    ) -> list[Match]:
        """:class:`Match` es of ``rows`` in order; ``parts``: row -> (distance, name part, vague part)."""
        snap = self.snapshot
        if metric == "jplog":
            terms = feature_terms(snap.log_scaled.num_rows(rows), snap.cat_rows(rows), query.log_scaled())
        else:  # the paper's JP terms (also shown for the baselines: why this object, in nats)
            terms = feature_terms(snap.num_rows(rows), snap.cat_rows(rows), query)
        out = []
        for i, row in enumerate(rows.tolist()):
            rec = snap.record(row)
            dist, name_part, vague_part = parts[row]
            out.append(
                Match(
                    name=snap.names[row],
                    distance=dist,
                    score=float(score[i]),
                    contributions={f: float(terms[f][i]) for f in query.stated},
                    matched_by_name=row in named_exact,
                    features={f: getattr(rec, f) for f in FEATURES},
                    name_part=name_part,
                    vague_part=vague_part,
                    kind=self.kinds.kind(row),
                )
            )
        return out

    def _same_kind(
        self, noun: DescribedNoun, query: FeatureQuery, metric: str, k: int = 3
    ) -> tuple[str | None, list[Match]]:
        """The ``k`` objects of the described noun's kind (or nearest ancestor) closest by features."""
        kind, rows = self.kinds.rows_of_kind(noun.kind)
        if not rows:
            return None, []
        arr = np.asarray(rows, dtype=np.int64)
        dist = self._distances_of(query, arr, metric) if len(query) else np.zeros(len(arr))
        arr, dist = select_top_k(arr, dist, min(k, len(arr)))
        parts = {int(r): (float(d), 0.0, 0.0) for r, d in zip(arr, dist, strict=True)}
        return kind, self._matches(arr, dist, parts, query, metric, set())


def _competitors(score: np.ndarray) -> float:
    """The ranking's effective number of candidates: sum of exp(-(s - s_best)) over the candidates scored
    (nats), i.e. 1 / the softmax posterior of the best; k tied objects and nothing else give k. A lower
    bound when not every row was scored."""
    if len(score) < 2:
        return 1.0
    rel = np.asarray(score, dtype=np.float64) - float(np.min(score))
    return float(np.sum(np.exp(-np.minimum(rel, 50.0))))
