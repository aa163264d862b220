"""Natural-language object descriptions to catalog features, offline with NLTK (no nltk_data).

This module is the parser's public face: :func:`parse`, :class:`DescriptionParser` and the result
records. The pipeline (the paper's Fig. 2) is one module per stage:

1. :mod:`recall.tokens`: ``nltk.tokenize.RegexpTokenizer`` splits the text (numbers, fractions, words,
   unit symbols), keeping character spans; multi-word expressions ("more than", "on each side",
   "fl oz") are merged.
2. :mod:`recall.tags`: ``nltk.tag.UnigramTagger`` tags each token from the domain lexicon
   (:mod:`recall.lexicon`), with a ``RegexpTagger`` for the rest (digits, fractions, other words); a
   linear pass fixes tags that depend on their neighbours ("in" inch or preposition, "x" a
   multiplication sign or a word, ...).
3. :mod:`recall.chunks`: a cascaded ``nltk.chunk.RegexpParser`` (:data:`GRAMMAR`) builds NUM, UNIT,
   HEDGE, RANGE, QUANT, MULTI and DIM chunks, one sentence at a time (sentences are capped at
   :data:`MAX_SEGMENT_TOKENS` tokens, which bounds the regular expressions' work: no catastrophic
   backtracking on long or hostile input).
4. :mod:`recall.quantities`: the chunks are read into quantities (numbers by :mod:`kb.measures.words`,
   units by :mod:`kb.measures.units`, pint once) and dimension statements; :mod:`recall.categories` reads
   the category words.
5. Resolution: :mod:`recall.dimensions` assigns the extents to a >= b >= c, :mod:`recall.mass` picks
   the mass, :mod:`recall.categories` one word per category (rules in ``recall/PARSER.md``).

:func:`parse` never raises on a ``str`` (nonsense gives an empty result); it raises
:class:`kb.errors.DescriptionError` only for a non-string or a text over :data:`MAX_TEXT_CHARS`.
"""

from __future__ import annotations

import functools
import threading
from dataclasses import dataclass, field
from typing import Any

from kb.errors import DescriptionError
from kb.features import FEATURES
from recall import lexicon as lx
from recall.categories import read_categories, resolve_categories
from recall.chunks import GRAMMAR, MAX_SEGMENT_TOKENS, Chunker, size
from recall.descriptions import MAX_DESCRIPTION_CHARS
from recall.dimensions import read_relations, resolve_dims
from recall.mass import resolve_mass
from recall.quantities import QuantityReader
from recall.reading import NEGATED_REASON, Reading, Stated
from recall.tags import Tagger
from recall.tokens import Tokenizer
from recall.toolkit import Tree
from recall.unread import read_unread

__all__ = [
    "GRAMMAR",
    "MAX_SEGMENT_TOKENS",
    "MAX_TEXT_CHARS",
    "QUALIFIERS",
    "DescriptionParser",
    "FeatureEvidence",
    "ParsedDescription",
    "RefusedQuantity",
    "parse",
]

#: Longest accepted description (characters; :data:`recall.descriptions.MAX_DESCRIPTION_CHARS`, the one
#: limit of every face); longer input raises DescriptionError.
MAX_TEXT_CHARS = MAX_DESCRIPTION_CHARS
QUALIFIERS: tuple[str, ...] = ("about", "exact", "at_least", "at_most", "range")


@dataclass(frozen=True)
class FeatureEvidence:
    """One stated feature: its value in catalog units (cm, g) or canonical category word, how it was
    qualified, and the words (character span) it came from."""

    feature: str
    value: float | str
    qualifier: str  # "about" | "exact" | "at_least" | "at_most" | "range"
    low: float | None
    high: float | None
    words: str
    start: int
    end: int

    def to_dict(self) -> dict[str, Any]:
        return {
            "value": self.value,
            "qualifier": self.qualifier,
            "low": self.low,
            "high": self.high,
            "words": self.words,
            "start": self.start,
            "end": self.end,
        }


@dataclass(frozen=True)
class RefusedQuantity:
    """A stated value the parser does not use, and why: negated ("not 10 cm"), negative ("-10 kg"), zero,
    beyond the catalog's limits ("1e308 cm", "10**100 g"; 5 m and 500 kg are accepted), too small to
    state, a second unit not smaller than one of the first ("5 ft 12 in"), or not read: a number followed
    by a word the parser knows no meaning of ("40 blorps", :mod:`recall.unread`)."""

    words: str
    start: int
    end: int
    reason: str

    def to_dict(self) -> dict[str, Any]:
        return {"words": self.words, "start": self.start, "end": self.end, "reason": self.reason}


@dataclass(frozen=True)
class ParsedDescription:
    """What a description states. ``features`` holds only the stated features: it is the per-feature
    mask the recall uses. ``mass_hint`` ("light"/"heavy") is a weak hint, never a mass: the recall
    engine decides whether and how to use it."""

    text: str
    features: dict[str, FeatureEvidence]
    mass_hint: str | None
    tree: Tree = field(compare=False, repr=False)
    #: stated values that are not used, in text order, each with its reason
    refused: tuple[RefusedQuantity, ...] = ()

    def values(self) -> dict[str, float | str]:
        """Feature -> value, for the stated features only."""
        return {f: ev.value for f, ev in self.features.items()}

    def is_empty(self) -> bool:
        """True when no feature is stated and there is no mass hint."""
        return not self.features and self.mass_hint is None

    def to_dict(self) -> dict[str, Any]:
        """JSON-able: every feature of :data:`kb.features.FEATURES` (null when not stated), then
        ``qualifiers``, ``evidence`` (per stated feature), ``mass_hint`` and ``refused`` (the stated values
        not used, with their reasons)."""
        out: dict[str, Any] = {f: (self.features[f].value if f in self.features else None) for f in FEATURES}
        out["mass_hint"] = self.mass_hint
        out["qualifiers"] = {f: ev.qualifier for f, ev in self.features.items()}
        out["evidence"] = {f: ev.to_dict() for f, ev in self.features.items()}
        out["text"] = self.text
        out["refused"] = [r.to_dict() for r in self.refused]
        return out


class DescriptionParser:
    """The stages (tokenizer, tagger, chunker, quantity reader with the unit table), built once;
    :meth:`parse` is thread-safe."""

    def __init__(self) -> None:
        self.tagger = Tagger()
        self.tokenizer = Tokenizer(self.tagger.model)
        self.chunker = Chunker()
        self.reader = QuantityReader()

    def parse(self, text: str) -> ParsedDescription:
        """Parse one description (see the module docstring)."""
        if not isinstance(text, str):
            raise DescriptionError(f"a description must be text, not {type(text).__name__}")
        if len(text) > MAX_TEXT_CHARS:
            raise DescriptionError(
                f"description too long: {len(text):,} characters (at most {MAX_TEXT_CHARS:,})"
            )
        return self.read(text)

    def read(self, text: str) -> ParsedDescription:
        """The stages on ``text`` of any length (no face calls it: the tests of the stages' own bounds on
        long hostile input do)."""
        try:
            tokens = self.tagger.tag(self.tokenizer.tokens(text))
        except TimeoutError:  # nltk.redos backstop on a regular expression; never expected
            return ParsedDescription(text=text, features={}, mass_hint=None, tree=Tree("S", []))
        reading = Reading()
        children: list[Any] = []
        pos = 0
        for segment in self.chunker.segments(tokens):
            tree = self.reader.join(self.chunker.chunk(segment))
            tree, requalified = _negate(tree, segment, pos, reading)
            children.extend(tree)
            self.reader.read(tree, segment, pos, reading)
            _requalify(reading, requalified)
            read_categories(segment, pos, reading)
            pos += len(segment)
        read_relations(tokens, reading)
        read_unread(tokens, reading)
        features, hint = _resolve(reading, text)
        refused = tuple(
            RefusedQuantity(text[start:end], start, end, reason)
            for (start, end), reason in sorted(reading.refused.items())
        )
        return ParsedDescription(
            text=text, features=features, mass_hint=hint, tree=Tree("S", children), refused=refused
        )


#: Chunks that state a value (a negation before one of them negates the value).
_VALUE_CHUNKS = frozenset({"QUANT", "MULTI", "DIM", "RANGE"})
#: What a negated bound or exact hedge becomes: "not over 10 cm" is at most 10, "not under" at least,
#: "not exactly 10 cm" about 10.
_NEGATED_HEDGE_TAGS = {"HL": "at_most", "HU": "at_least", "HX": "about"}


def _negation(segment: list[Any], k: int) -> str | None:
    """How the value chunk starting at token ``k`` is negated: None when it is not, "" by a plain
    negation right before it ("not 10 cm", "does not weigh 300 g", "isn't really 10 cm", "not filled
    with 500 ml": at most two BE, FILL or :data:`~recall.lexicon.NEGATION_GAP_WORDS` words between), or
    the qualifier of a :data:`~recall.lexicon.NEGATED_HEDGE_WORDS` word between ("not quite 10 cm":
    about)."""
    hedge = ""
    for gap, j in enumerate(range(k - 1, max(-1, k - 4), -1)):
        tok = segment[j]
        if tok.tag == "NEG":
            return hedge if tok.low in lx.VALUE_NEGATIONS else None
        if gap == 0 and tok.low in lx.NEGATED_HEDGE_WORDS:
            hedge = lx.NEGATED_HEDGE_WORDS[tok.low]
        elif gap == 2 or not (tok.tag in ("BE", "FILL") or tok.low in lx.NEGATION_GAP_WORDS):
            return None
    return None


def _negate(
    tree: Tree, segment: list[Any], pos: int, reading: Reading
) -> tuple[Tree, dict[tuple[int, int], str]]:
    """The sentence's chunk tree with each negated value chunk taken apart into its words (the value is not
    stated: listed in ``reading.refused``), and the spans of the negated chunks whose value is kept with
    another qualifier ("not more than 10 cm" at most, "not exactly 10 cm" about, "not quite 10 cm" about)."""
    kept: list[Any] = []
    requalified: dict[tuple[int, int], str] = {}
    k = 0
    for child in tree:
        if not isinstance(child, Tree):
            kept.append(child)
            k += 1
            continue
        n = size(child)
        how = _negation(segment, k) if child.label() in _VALUE_CHUNKS else None
        toks = segment[k : k + n]
        hedges = [t.tag for t in toks if t.tag in ("HA", "HL", "HU", "HX")]
        if how is None:
            kept.append(child)
        elif how or (hedges and hedges[0] in _NEGATED_HEDGE_TAGS):
            kept.append(child)
            requalified[(toks[0].start, toks[-1].end)] = how or _NEGATED_HEDGE_TAGS[hedges[0]]
        else:
            kept.extend(child.leaves())
            reading.refuse(toks[0].start, toks[-1].end, NEGATED_REASON)
            if any(t.tag in ("DIM", "DIMN") for t in toks):
                reading.in_dim_chunk.update(range(pos + k, pos + k + n))  # "not 10 cm long": no long shape
        k += n
    return (Tree(tree.label(), kept) if len(kept) != len(tree) else tree), requalified


def _requalify(reading: Reading, spans: dict[tuple[int, int], str]) -> None:
    """Give each quantity read inside one of ``spans`` that span's qualifier (a range stays a range)."""
    if not spans:
        return
    quantities = [q for stmt in (*reading.dims, *reading.multis, *reading.sizes) for q in stmt.quantities]
    quantities += [q for q, _contents in reading.masses] + reading.other_masses + reading.contents
    for q in quantities:
        qualifier = next((v for (a, b), v in spans.items() if a <= q.start and q.end <= b), None)
        if qualifier is None or q.qualifier == "range":
            continue
        q.qualifier = qualifier
        q.low = q.value if qualifier == "at_least" else None
        q.high = q.value if qualifier == "at_most" else None


#: A length in parentheses right after another restates it (a unit conversion, a closer figure) when the
#: two agree within this factor: "a bit over a metre (about 115 cm)", "2 m (6.5 ft)".
RESTATED_FACTOR = 1.5


def _length_cm(stmt) -> float | None:
    q = stmt.quantities[0] if len(stmt.quantities) == 1 else None
    if q is None or q.unit is None or q.unit.kind != "length":
        return None
    return q.value * q.unit.factor


def drop_restatements(reading: Reading, text: str) -> None:
    """Drop each single length in parentheses that restates the length stated right before it (only
    spaces and the opening parenthesis between them, agreeing within :data:`RESTATED_FACTOR`): "a bit over
    a metre (about 115 cm)" is one extent, not a 115 cm length and a 100 cm width; "10 inches (25 cm)
    long, 4 in (10 cm) wide" is two. The first statement stays (it has the position the words give)."""
    stmts = sorted((*reading.dims, *reading.sizes), key=lambda st: st.start)
    restated = set()
    for before, stmt in zip(stmts, stmts[1:], strict=False):
        gap = text[before.end : stmt.start]
        if gap.strip() != "(" or not text[stmt.end :].lstrip().startswith(")"):
            continue
        x, y = _length_cm(before), _length_cm(stmt)
        if x and y and max(x, y) / min(x, y) <= RESTATED_FACTOR:
            restated.add(id(stmt))
    if restated:
        reading.dims[:] = [st for st in reading.dims if id(st) not in restated]
        reading.sizes[:] = [st for st in reading.sizes if id(st) not in restated]


def _resolve(reading: Reading, text: str) -> tuple[dict[str, FeatureEvidence], str | None]:
    """The features (in :data:`kb.features.FEATURES` order) and the mass hint of a reading."""
    features: dict[str, FeatureEvidence] = {}
    drop_restatements(reading, text)
    for name, dim in resolve_dims(reading).items():
        features[name] = _evidence(name, dim, text)
    mass = resolve_mass(reading)
    if mass is not None:
        features["mass_g"] = _evidence("mass_g", mass, text)
    for feature, (value, tok) in resolve_categories(reading).items():
        features[feature] = FeatureEvidence(feature, value, "exact", None, None, tok.word, tok.start, tok.end)
    hint = reading.mass_hints[0] if reading.mass_hints else None
    ordered = {f: features[f] for f in FEATURES if f in features}
    return ordered, hint


def _evidence(name: str, stated: Stated, text: str) -> FeatureEvidence:
    """A numeric feature's evidence, rounded to 4 decimals in catalog units."""
    return FeatureEvidence(
        name, round(stated.value, 4), stated.qualifier, _r(stated.low), _r(stated.high),
        text[stated.start : stated.end], stated.start, stated.end,
    )  # fmt: skip


def _r(value: float | None) -> float | None:
    return None if value is None else round(value, 4)


@functools.cache
def _default_parser() -> DescriptionParser:
    return DescriptionParser()


_build_lock = threading.Lock()


def default_parser() -> DescriptionParser:
    """The module-level parser, built on first use."""
    with _build_lock:
        return _default_parser()


def parse(text: str) -> ParsedDescription:
    """Parse a description with the module-level :class:`DescriptionParser` (built on first use)."""
    return default_parser().parse(text)
