"""Natural-language object descriptions to catalog features, offline with NLTK (no nltk_data).

The pipeline (the paper's Fig. 2), built once by :class:`DescriptionParser`:

1. ``nltk.tokenize.RegexpTokenizer`` splits the text (numbers, fractions, words, unit symbols), keeping
   character spans; multi-word expressions ("more than", "on each side", "fl oz") are merged.
2. ``nltk.tag.UnigramTagger`` tags each token from the domain lexicon (:mod:`recall.lexicon`), with a
   ``RegexpTagger`` for the rest (digits, fractions, other words); a linear pass fixes tags that depend
   on their neighbours ("in" inch or preposition, "x" a multiplication sign or a word, ...).
3. A cascaded ``nltk.chunk.RegexpParser`` (:data:`GRAMMAR`) builds NUM, UNIT, HEDGE, RANGE, QUANT,
   MULTI and DIM chunks, one sentence at a time (sentences are capped at
   :data:`MAX_SEGMENT_TOKENS` tokens, which bounds the regular expressions' work: no catastrophic
   backtracking on long or hostile input).
4. The chunks are read into features: numbers by :mod:`recall.numbers`, units by :mod:`recall.units`
   (pint, once), dimensions assigned to a >= b >= c by the rules in ``recall/PARSER.md``.

:func:`parse` never raises on a ``str`` (nonsense gives an empty result); it raises
:class:`kb.errors.DescriptionError` only for a non-string or a text over :data:`MAX_TEXT_CHARS`.
"""

from __future__ import annotations

import functools
import re
import threading
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

from nltk.chunk import RegexpChunkParser, RegexpParser
from nltk.chunk.regexp import ChunkString
from nltk.tag import RegexpTagger, UnigramTagger
from nltk.tokenize import RegexpTokenizer
from nltk.tree import Tree

from kb.errors import DescriptionError
from kb.features import FEATURES, MAX_DIM_CM, MAX_MASS_G
from recall import lexicon as lx
from recall.numbers import DIGITS_PATTERN, number_value
from recall.units import Unit, unit_table

__all__ = [
    "GRAMMAR",
    "MAX_SEGMENT_TOKENS",
    "MAX_TEXT_CHARS",
    "QUALIFIERS",
    "DescriptionParser",
    "FeatureEvidence",
    "ParsedDescription",
    "parse",
]

#: Longest accepted description (characters); longer input raises DescriptionError.
MAX_TEXT_CHARS = 1_000_000
#: A sentence longer than this many tokens is chunked in pieces of this size.
MAX_SEGMENT_TOKENS = 48
QUALIFIERS: tuple[str, ...] = ("about", "exact", "at_least", "at_most", "range")

_FRACTION_CHARS = "".join(lx.UNICODE_FRACTIONS)
#: Tokens: numbers in digits, unicode fractions, words (with inner apostrophes and hyphens), unit
#: symbols and the punctuation the grammar uses. Unmatched characters are skipped. No nested quantifiers.
TOKEN_PATTERN = (
    DIGITS_PATTERN
    + r"|[" + _FRACTION_CHARS + r"]"
    + r"|[^\W\d_]+(?:['’-][^\W\d_]+)*"
    + r"|''|[\"”″'′’]"
    + r"|\+/-|\+-|±"
    + r"|[×~≈*=:;,.!?()&–—-]"
)  # fmt: skip

#: The cascaded chunk grammar (one stage per label, applied in this order).
GRAMMAR = r"""
NUM:
  {<A>?<CD|NW|NMAG>+<AND><A>?<NW>?<FRC>}
  {<A>?<CD|NW>*<NMAG><AND><NW>+}
  {<A>?<CD|NW|NMAG>*<FRC>+}
  {<A>?<CD|NW|NMAG>+}
UNIT:
  {<ULEN|UMASS|UVOL>}
HEDGE:
  {<HA|HL|HU|HX>+}
RANGE:
  {<BETW><NUM><UNIT>?<AND|RTO><NUM>}
  {<NUM><UNIT>?<RTO><NUM>}
SUB:
  {<USUB>}
QUANT:
  {<LBL>?<HEDGE>?<NUM><UNIT><NUM><SUB><HS|LBL>?}
  {<LBL>?<HEDGE>?<NUM><OF>?<A>?<UNIT><UAND><NUM><HS>?}
  {<LBL>?<HEDGE>?<NUM|RANGE><HS|LBL>?<OF>?<A>?<UNIT><HS|LBL>?}
  {<LBL>?<HEDGE>?<NUM|RANGE><HS|LBL>?}
MULTI:
  {<QUANT><DIM|DIMN>?<BY><QUANT><DIM|DIMN>?<BY><QUANT><IN>?<DIM|DIMN>?}
  {<QUANT><DIM|DIMN>?<BY><QUANT><IN>?<DIM|DIMN>?}
  {<QUANT><CM><QUANT><CM><AND>?<QUANT><IN>?<DIM>?}
  {<QUANT><CM><QUANT><AND><QUANT><IN>?<DIM>?}
DIM:
  {<DIMN><BE|OF|IN|W>?<BE|OF|IN|W>?<BE|OF|IN|W>?<QUANT>}
  {<QUANT><IN|OF>?<DIM|DIMN>}
"""


#: When a stage can match: each listed tag set must meet the sentence's tags (or earlier chunks).
_STAGE_TRIGGERS: dict[str, tuple[frozenset[str], ...]] = {
    "NUM": (frozenset({"CD", "NW", "NMAG", "FRC"}),),
    "UNIT": (frozenset({"ULEN", "UMASS", "UVOL"}),),
    "HEDGE": (frozenset({"HA", "HL", "HU", "HX"}),),
    "RANGE": (frozenset({"NUM"}), frozenset({"RTO", "BETW"})),
    "SUB": (frozenset({"USUB"}),),
    "QUANT": (frozenset({"NUM", "RANGE"}),),
    "MULTI": (frozenset({"QUANT"}), frozenset({"BY", "CM"})),
    "DIM": (frozenset({"QUANT"}), frozenset({"DIM", "DIMN"})),
}


def _required_tags(rule_text: str) -> tuple[frozenset[str], ...]:
    """The tag groups a rule cannot match without: every ``<A|B>`` not marked optional (``?``/``*``)."""
    groups = []
    for m in re.finditer(r"<([A-Z|]+)>([?*+]?)", rule_text):
        if m.group(2) not in ("?", "*"):
            groups.append(frozenset(m.group(1).split("|")))
    return tuple(groups)


_BRACES = re.compile(r"[{}]")


class _Tokenizer(RegexpTokenizer):
    """nltk's RegexpTokenizer over the fixed :data:`TOKEN_PATTERN`, compiled with the standard ``re``
    engine. nltk routes a *caller-supplied* pattern through ``nltk.redos`` (the ``regex`` engine with a
    wall-clock timeout on every call), which costs more than the matching itself; our pattern is a
    constant without nested quantifiers, and the hostile-input tests (100 KB digit-comma, hyphen and
    quote chains) show it stays linear."""

    def _check_regexp(self) -> None:
        if self._regexp is None:
            self._regexp = re.compile(self._pattern, self._flags)


class _ChunkString(ChunkString):
    """nltk's ChunkString built without its self-check (debug_level 0) and with the tag string made in
    one expression (the same string ``<A><CD>...`` as nltk's)."""

    def __init__(self, chunk_struct: Tree) -> None:
        self._root_label = chunk_struct.label()
        self._pieces = chunk_struct[:]
        tags = [p.label() if isinstance(p, Tree) else p[1] for p in self._pieces]
        self._str = "<" + "><".join(tags) + ">"
        self._debug = 0

    def xform(self, regexp, repl) -> None:
        """As nltk's, with the empty-chunk cleanup done by str.replace instead of a second regex."""
        s = regexp.sub(repl, self._str)
        self._str = s.replace("{}", "") if "{}" in s else s

    def to_chunkstruct(self, chunk_label: str = "CHUNK") -> Tree:
        """As nltk's, splitting on the braces with a precompiled standard pattern."""
        pieces: list[Any] = []
        index = 0
        in_chunk = False
        for piece in _BRACES.split(self._str):
            length = piece.count("<")
            if in_chunk:
                pieces.append(Tree(chunk_label, self._pieces[index : index + length]))
            else:
                pieces += self._pieces[index : index + length]
            index += length
            in_chunk = not in_chunk
        return Tree(self._root_label, pieces)


class _QuietStage(RegexpChunkParser):
    """One stage of the cascade: nltk's RegexpChunkParser without ChunkString's per-call self-check
    (debug_level=0; the grammar is fixed and tested), applying only the rules whose required tags are
    present in the sentence."""

    def __init__(self, rules, chunk_label, root_label="S", trace=0):
        super().__init__(rules, chunk_label=chunk_label, root_label=root_label, trace=trace)
        self.triggers = _STAGE_TRIGGERS[chunk_label]
        # each rule's regular expression (nltk builds it from the tag pattern) recompiled with the
        # standard engine, for the reason given at _Tokenizer: the grammar is a tested constant and a
        # sentence is at most MAX_SEGMENT_TOKENS tags long
        self.fast = [
            (
                _required_tags(rule.descr() if rule.descr() else str(rule)),
                re.compile(rule._regexp.pattern),
                rule._repl,
            )
            for rule in rules
        ]

    def chunk(self, tree: Tree, present: set[str]) -> Tree | None:
        """The tree with this stage's chunks, or None when the stage found none (the tree is unchanged)."""
        chunkstr = _ChunkString(tree)
        for required, regexp, repl in self.fast:
            if all(present & group for group in required):
                chunkstr.xform(regexp, repl)
        if "{" not in chunkstr._str:
            return None
        return chunkstr.to_chunkstruct(self._chunk_label)


class _Cascade(RegexpParser):
    """nltk's cascaded RegexpParser over :data:`GRAMMAR`, skipping a stage that cannot match the
    sentence (:data:`_STAGE_TRIGGERS`; most sentences need only a few of the seven stages)."""

    def _add_stage(self, rules, lhs, root_label, trace):  # nltk's hook: build our quiet stages
        if rules:
            self._stages.append(_QuietStage(rules, chunk_label=lhs, root_label=root_label, trace=trace))

    def parse(self, chunk_struct, trace=None) -> Tree:
        pairs = list(chunk_struct)
        present = {tag for _word, tag in pairs}
        tree = Tree("S", pairs)
        for stage in self._stages:
            if all(present & group for group in stage.triggers):
                chunked = stage.chunk(tree, present)
                if chunked is not None:
                    tree = chunked
                    present.add(stage._chunk_label)
        return tree


#: Most words remembered by a parser's tag cache (new words past this are tagged, not remembered).
_TAG_CACHE_SIZE = 100_000
_NUMBER_TAGS = frozenset({"CD", "NW", "NMAG", "FRC"})
_UNIT_TAGS = frozenset({"ULEN", "UMASS", "UVOL"})
_CATEGORY_TAGS = {"MAT": "material", "SHP": "shape", "RIG": "rigidity", "TEX": "texture", "FRA": "fragility"}
#: Tags worth chunking a sentence for; a sentence without any is left flat.
_INTERESTING = _NUMBER_TAGS | _UNIT_TAGS | {"DIM", "DIMN", "MAT", "SHP", "RIG", "TEX", "FRA", "MH"}
_ABBREVIATIONS = frozenset(
    {"in", "ft", "oz", "lb", "lbs", "approx", "ca", "cm", "mm", "dia", "diam", "no", "vs", "e", "g", "i",
     "kg", "ml", "fl", "m", "l", "gm", "gms", "dl", "cl", "st", "mr", "dr"}
)  # fmt: skip
_SYMBOL_UNITS = frozenset({'"', "''", "”", "″", "'", "′", "’"})


# ------------------------------------------------------------------------------------------ the result
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
class ParsedDescription:
    """What a description states. ``features`` holds only the stated features: it is the per-feature
    mask the recall uses. ``mass_hint`` ("light"/"heavy") is a weak hint, never a mass: the recall
    engine decides whether and how to use it."""

    text: str
    features: dict[str, FeatureEvidence]
    mass_hint: str | None
    tree: Tree = field(compare=False, repr=False)

    def values(self) -> dict[str, float | str]:
        """Feature -> value, for the stated features only."""
        return {f: ev.value for f, ev in self.features.items()}

    def is_empty(self) -> bool:
        """True when no feature is stated and there is no mass hint."""
        return not self.features and self.mass_hint is None

    def to_dict(self) -> dict[str, Any]:
        """JSON-able: every feature of :data:`kb.features.FEATURES` (null when not stated), then
        ``qualifiers``, ``evidence`` (per stated feature) and ``mass_hint``."""
        out: dict[str, Any] = {f: (self.features[f].value if f in self.features else None) for f in FEATURES}
        out["mass_hint"] = self.mass_hint
        out["qualifiers"] = {f: ev.qualifier for f, ev in self.features.items()}
        out["evidence"] = {f: ev.to_dict() for f, ev in self.features.items()}
        out["text"] = self.text
        return out


# ------------------------------------------------------------------------------------ internal records
@dataclass(slots=True)
class _Token:
    word: str  # surface text
    low: str  # lower-case lookup form (merged words joined by one space)
    start: int
    end: int
    tag: str = "W"


@dataclass(slots=True)
class _Quantity:
    value: float
    low: float | None
    high: float | None
    qualifier: str
    unit: Unit | None
    start: int
    end: int
    pos: int  # token index in the text (for unit inheritance)


@dataclass
class _DimStatement:
    role: str
    quantities: list[_Quantity]
    start: int
    end: int


@dataclass
class _Relation:
    """An extent stated relative to another ("twice as long as it is wide"): ``role`` is ``factor``
    times ``ref`` (None: the extent stated last before it, as in "6 cm wide and three times as long")."""

    role: str
    factor: float
    ref: str | None
    start: int
    end: int


@dataclass
class _Reading:
    """Everything read from the chunks, in text order, before the features are resolved."""

    dims: list[_DimStatement] = field(default_factory=list)
    multis: list[_DimStatement] = field(default_factory=list)
    sizes: list[_DimStatement] = field(default_factory=list)
    masses: list[tuple[_Quantity, bool]] = field(default_factory=list)  # (quantity, is contents)
    other_masses: list[_Quantity] = field(default_factory=list)  # "my 2 kg dumbbell": used only alone
    contents: list[_Quantity] = field(default_factory=list)
    length_units: list[tuple[int, Unit]] = field(default_factory=list)  # (token index, unit)
    categories: dict[str, list[tuple[int, int, str, _Token]]] = field(default_factory=dict)
    mass_hints: list[str] = field(default_factory=list)
    cue_words: set[str] = field(default_factory=set)
    in_dim_chunk: set[int] = field(default_factory=set)
    relations: list[_Relation] = field(default_factory=list)


# ------------------------------------------------------------------------------------------ the parser
class DescriptionParser:
    """The tokenizer, tagger, chunker and unit table, built once; :meth:`parse` is thread-safe."""

    def __init__(self) -> None:
        self._tokenizer = _Tokenizer(TOKEN_PATTERN)
        fallback = RegexpTagger(
            [
                (r"^(?:" + DIGITS_PATTERN + r")$", "CD"),
                (r"^[" + _FRACTION_CHARS + r"]$", "FRC"),
                (r"^(?:twenty|thirty|forty|fourty|fifty|sixty|seventy|eighty|ninety)-"
                 r"(?:one|two|three|four|five|six|seven|eight|nine)$", "NW"),
                (r".*", "W"),
            ]
        )  # fmt: skip
        self._model = lx.tag_model()
        self._tagger = UnigramTagger(model=self._model, backoff=fallback)
        # word -> tag: the unigram tagger looks at one word only, so its answer for a word never changes
        self._tag_cache: dict[str, str] = {}
        self._chunker = _Cascade(GRAMMAR)
        self._units = unit_table()
        mwe: dict[tuple[str, ...], str] = {}
        for phrase in lx.MULTIWORD:
            mwe[tuple(phrase.split())] = phrase
        self._mwe = mwe
        self._mwe_first = {k[0] for k in mwe}
        self._mwe_max = max((len(k) for k in mwe), default=1)

    # -- public
    def parse(self, text: str) -> ParsedDescription:
        """Parse one description (see the module docstring)."""
        if not isinstance(text, str):
            raise DescriptionError(f"a description must be text, not {type(text).__name__}")
        if len(text) > MAX_TEXT_CHARS:
            raise DescriptionError(
                f"description too long: {len(text):,} characters (at most {MAX_TEXT_CHARS:,})"
            )
        try:
            tokens = self._tag(self._tokens(text))
        except TimeoutError:  # nltk.redos backstop on a regular expression; never expected
            return ParsedDescription(text=text, features={}, mass_hint=None, tree=Tree("S", []))
        reading = _Reading()
        children: list[Any] = []
        pos = 0
        for segment in self._segments(tokens):
            tree = self._chunk(segment)
            children.extend(tree)
            self._read(tree, segment, pos, reading)
            pos += len(segment)
        _read_relations(tokens, reading)
        features, hint = _resolve(reading, tokens, text)
        return ParsedDescription(text=text, features=features, mass_hint=hint, tree=Tree("S", children))

    # -- 1. tokens
    def _tokens(self, text: str) -> list[_Token]:
        raw: list[_Token] = []
        model = self._model
        for start, end in self._tokenizer.span_tokenize(text):
            word = text[start:end]
            low = word.lower()
            if "’" in low:
                low = low.replace("’", "'")
            if (
                "-" in low
                and len(low) > 1
                and low not in model
                and low not in lx.TOLERANCE_WORDS
                and _split_hyphen(low)
            ):
                # "5-cm-long" parts, "non-fragile" -> non fragile; number compounds stay whole
                offset = start
                for part in word.split("-"):
                    if part:
                        raw.append(_Token(part, part.lower(), offset, offset + len(part)))
                    offset += len(part) + 1
                continue
            raw.append(_Token(word, low, start, end))
        # merge multi-word expressions, longest first
        if self._mwe_first.isdisjoint(t.low for t in raw):
            return raw
        out: list[_Token] = []
        i = 0
        n = len(raw)
        while i < n:
            tok = raw[i]
            if tok.low in self._mwe_first:
                for size in range(min(self._mwe_max, n - i), 1, -1):
                    key = tuple(t.low for t in raw[i : i + size])
                    phrase = self._mwe.get(key)
                    if phrase is not None:
                        last = raw[i + size - 1]
                        out.append(_Token(text[tok.start : last.end], phrase, tok.start, last.end))
                        i += size
                        break
                else:
                    out.append(tok)
                    i += 1
            else:
                out.append(tok)
                i += 1
        return out

    # -- 2. tags
    def _tag(self, tokens: list[_Token]) -> list[_Token]:
        cache = self._tag_cache
        missing = list({t.low for t in tokens if t.low not in cache})
        fresh: dict[str, str] = {}
        if missing:
            fresh = {w: (tag or "W") for w, tag in self._tagger.tag(missing)}
            if len(cache) < _TAG_CACHE_SIZE:
                cache.update(fresh)  # one dict update: safe for concurrent parses
        for tok in tokens:
            tag = cache.get(tok.low)
            tok.tag = tag if tag is not None else fresh[tok.low]
        return _fix_tags(tokens)

    # -- sentences
    def _segments(self, tokens: list[_Token]) -> Iterator[list[_Token]]:
        seg: list[_Token] = []
        for tok in tokens:
            seg.append(tok)
            if tok.tag == "SEP" or len(seg) >= MAX_SEGMENT_TOKENS:
                yield seg
                seg = []
        if seg:
            yield seg

    # -- 3. chunks
    def _chunk(self, segment: list[_Token]) -> Tree:
        pairs = [(t.word, t.tag) for t in segment]
        if not any(t.tag in _INTERESTING for t in segment):
            return Tree("S", pairs)
        try:
            return self._chunker.parse(pairs)
        except (TimeoutError, ValueError, RecursionError):  # nltk.redos backstop; never expected
            return Tree("S", pairs)

    # -- 4. reading
    def _read(self, tree: Tree, segment: list[_Token], base: int, reading: _Reading) -> None:
        fill = _fill_context(segment)
        k = 0
        for idx, child in enumerate(tree):
            if isinstance(child, Tree):
                n = _size(child)
                toks = segment[k : k + n]
                if child.label() == "QUANT" and idx + 1 < len(tree) and _noun_took_other_unit(tree[idx + 1]):
                    # "~ 10cm diameter ~ 0.8 kg": the noun's value is the length before it, not the mass
                    q = self._quantity(child, toks, base + k)
                    role = lx.DIMENSION_WORDS.get(segment[k + n].low, "size")
                    if (
                        q is not None
                        and q.unit is not None
                        and q.unit.kind == "length"
                        and role in _NOUN_ROLES
                    ):
                        self._add_dim(reading, role, [q], segment[k : k + n + 1], base + k)
                        k += n
                        continue
                self._read_chunk(child, toks, base + k, reading, fill, segment, k)
                k += n
            else:
                k += 1
        _read_categories(segment, base, reading)

    def _read_chunk(
        self,
        chunk: Tree,
        toks: list[_Token],
        pos: int,
        reading: _Reading,
        fill: int | None,
        segment: list[_Token],
        k: int,
    ) -> None:
        label = chunk.label()
        if label == "QUANT":
            q = self._quantity(chunk, toks, pos)
            if q is not None:
                self._free_quantity(q, toks, reading, fill, segment, k)
            return
        if label == "MULTI":
            self._read_multi(chunk, toks, pos, reading, fill, segment, k)
            return
        if label != "DIM":
            return
        quants: list[_Quantity] = []
        role = "size"
        dim_word: _Token | None = None
        dim_first = False
        j = 0
        for sub in chunk:
            if isinstance(sub, Tree):
                n = _size(sub)
                if sub.label() == "QUANT":
                    q = self._quantity(sub, toks[j : j + n], pos + j)
                    if q is not None:
                        quants.append(q)
                j += n
            else:
                tok = toks[j]
                if tok.tag in ("DIM", "DIMN"):
                    dim_word = tok
                    dim_first = not quants
                    role = lx.DIMENSION_WORDS.get(tok.low, "size")
                j += 1
        if not quants:
            return
        if any(q.unit is not None and q.unit.kind != "length" for q in quants):
            for q in quants:  # "tall, about 300 g": not a dimension
                if q.unit is not None:
                    self._free_quantity(q, toks, reading, fill, segment, k)
            return
        if dim_word is not None and dim_word.low in lx.WEAK_DIMENSION_WORDS:
            if dim_first or quants[0].unit is None:
                return  # "a large bottle, 2": no dimension
            role = "size"
        if dim_word is not None and dim_word.low in lx.UNIT_ONLY_DIMENSION_WORDS:
            if dim_first or quants[0].unit is None:
                return  # "10 square", "square 5": not "9 cm square"
        end = k + len(toks)
        if role in ("length", "height") and end < len(segment) and segment[end].tag == "DIM":
            if lx.DIMENSION_WORDS.get(segment[end].low) == "overall":
                role = "overall"  # "30 cm long overall", "48 cm long with the handle"
        self._add_dim(reading, role, quants, toks, pos)

    @staticmethod
    def _add_dim(reading: _Reading, role: str, quants: list[_Quantity], toks: list[_Token], pos: int) -> None:
        for i in range(pos, pos + len(toks)):
            reading.in_dim_chunk.add(i)
        for q in quants:
            if q.unit is not None:
                reading.length_units.append((q.pos, q.unit))
        stmt = _DimStatement(role, quants, toks[0].start, toks[-1].end)
        if role == "multi":
            reading.multis.append(stmt)
        elif role == "size":
            reading.sizes.append(stmt)
        else:
            reading.dims.append(stmt)

    def _read_multi(
        self,
        chunk: Tree,
        toks: list[_Token],
        pos: int,
        reading: _Reading,
        fill: int | None,
        segment: list[_Token],
        k: int,
    ) -> None:
        """A tuple ("10 x 5 x 2 cm", "7.5 cm long by 5 by 5", "L 20 x W 10 x H 5 cm") or a list ("20, 10
        and 5 cm"). Numbers without a unit take the unit of the next one in the tuple that has one, else
        of the previous one. A tuple whose every value has its own dimension word ("10 cm long by 3 cm in
        diameter") is read as those dimensions; a list counts only when its last value has a length
        unit, otherwise its values are read one by one."""
        quants: list[_Quantity] = []
        roles: list[str | None] = []
        spans: list[tuple[int, int]] = []
        is_list = False
        j = 0
        for sub in chunk:
            if isinstance(sub, Tree):
                n = _size(sub)
                if sub.label() == "QUANT":
                    q = self._quantity(sub, toks[j : j + n], pos + j)
                    if q is not None:
                        quants.append(q)
                        roles.append(None)
                        spans.append((j, j + n))
                j += n
            else:
                tok = toks[j]
                if tok.tag in ("DIM", "DIMN") and quants and roles[-1] is None:
                    roles[-1] = lx.DIMENSION_WORDS.get(tok.low, "size")
                    spans[-1] = (spans[-1][0], j + 1)
                elif tok.tag in ("CM", "AND"):
                    is_list = True
                j += 1
        if not quants:
            return
        if is_list and (quants[-1].unit is None or quants[-1].unit.kind != "length"):
            for q in quants:  # "300 g, 20 cm and 5": not one list of extents
                self._free_quantity(q, toks, reading, fill, segment, k)
            return
        stated = [q.unit for q in quants]
        for i, q in enumerate(quants):
            if q.unit is None:
                after = next((u for u in stated[i + 1 :] if u is not None), None)
                before = next((u for u in reversed(stated[:i]) if u is not None), None)
                q.unit = after or before
        if any(q.unit is not None and q.unit.kind != "length" for q in quants):
            for q in quants:  # "tall, about 300 g": not a dimension
                if q.unit is not None:
                    self._free_quantity(q, toks, reading, fill, segment, k)
            return
        if len(quants) < 2:
            return
        weak = lx.WEAK_DIMENSION_WORDS | lx.UNIT_ONLY_DIMENSION_WORDS
        if not is_list and len(quants) == 2 and set(roles) in ({"diameter", None}, {"radius", None}):
            roles = [r or "length" for r in roles]  # "7 cm dia x 12 cm": the other extent of a cylinder
        if not is_list and all(r is not None and r != "size" for r in roles):
            for q, role, (a, b) in zip(quants, roles, spans, strict=True):
                if role is not None and role not in weak:
                    self._add_dim(reading, role, [q], toks[a:b], pos + a)
            return
        self._add_dim(reading, "multi", quants, toks, pos)

    def _free_quantity(
        self,
        q: _Quantity,
        toks: list[_Token],
        reading: _Reading,
        fill: int | None,
        segment: list[_Token],
        k: int,
    ) -> None:
        """A quantity outside any dimension chunk: a mass, contents, or an unlabelled length."""
        if q.unit is None:
            return
        other = _other_object(segment, k)
        if other == "compared":
            return  # "it sits next to my 2 kg dumbbell": another object's mass or size
        if other == "owned" and q.unit.kind == "mass":
            reading.other_masses.append(q)  # "my 2 kg dumbbell": the object itself only if nothing else
            return
        contents = fill is not None and (fill < k or segment[fill].low not in lx.WEAK_FILL_WORDS)
        if q.unit.kind == "mass":
            if contents:
                # "filled with 16 oz of water" is contents; "full of water, about a pound and a half" is
                # the stated total: only a mass right after the contents word or before "of" is contents
                end = k + len(toks)
                after_of = end < len(segment) and segment[end].low == "of"
                right_after = fill is not None and 0 < k - fill <= 2
                contents = after_of or right_after
            reading.masses.append((q, contents))
        elif q.unit.kind == "volume":
            if contents:
                reading.contents.append(q)
        elif q.unit.kind == "length":
            reading.length_units.append((q.pos, q.unit))
            reading.sizes.append(_DimStatement("size", [q], q.start, q.end))

    def _quantity(self, chunk: Tree, toks: list[_Token], pos: int) -> _Quantity | None:
        """Read a QUANT chunk: hedge, number or range, unit."""
        qualifier = "exact"
        plus = False
        numbers: list[float] = []
        unit: Unit | None = None
        j = 0
        for sub in chunk:
            if isinstance(sub, Tree):
                n = _size(sub)
                part = toks[j : j + n]
                label = sub.label()
                if label == "HEDGE":
                    qualifier = _hedge_qualifier(part)
                elif label == "NUM":
                    value = _num(part)
                    if value is None:
                        return None
                    if plus and numbers:
                        numbers[-1] += value  # "an inch and a half"
                    else:
                        numbers.append(value)
                elif label == "RANGE":
                    r = 0
                    for rsub in sub:
                        if isinstance(rsub, Tree):
                            rn = _size(rsub)
                            if rsub.label() == "NUM":
                                value = _num(part[r : r + rn])
                                if value is None:
                                    return None
                                numbers.append(value)
                            elif rsub.label() == "UNIT":
                                unit = self._units.get(part[r].low)
                            r += rn
                        else:
                            r += 1
                elif label == "UNIT":
                    unit = self._units.get(part[0].low)
                elif label == "SUB":  # "1 lb 2 oz", "5 ft 3 in": one quantity in two units
                    sub_unit = self._units.get(part[0].low)
                    if unit is not None and sub_unit is not None and len(numbers) == 2:
                        numbers = [numbers[0] + numbers[1] * sub_unit.factor / unit.factor]
                j += n
            else:
                if toks[j].tag == "HS":
                    qualifier = "about"
                plus = toks[j].tag == "UAND"
                j += 1
        if not numbers:
            return None
        start, end = toks[0].start, toks[-1].end
        if len(numbers) >= 2:
            lo, hi = sorted(numbers[:2])
            if lo <= 0:
                return None
            return _Quantity((lo + hi) / 2, lo, hi, "range", unit, start, end, pos)
        value = numbers[0]
        if value <= 0:
            return None
        low = value if qualifier == "at_least" else None
        high = value if qualifier == "at_most" else None
        return _Quantity(value, low, high, qualifier, unit, start, end, pos)


_NOUN_ROLES = frozenset({*lx.LINEAR_ROLES, "diameter", "radius"})


def _noun_took_other_unit(node: Any) -> bool:
    """True for a DIM chunk "<dimension noun> <quantity>" whose quantity is a mass or a volume."""
    if (
        not isinstance(node, Tree)
        or node.label() != "DIM"
        or isinstance(node[0], Tree)
        or node[0][1] != "DIMN"
    ):
        return False
    for sub in node:
        if isinstance(sub, Tree) and sub.label() == "QUANT":
            return any(
                isinstance(u, Tree) and u.label() == "UNIT" and u[0][1] in ("UMASS", "UVOL") for u in sub
            )
    return False


# ---------------------------------------------------------------------------------------- tag context
def _read_relations(tokens: list[_Token], reading: _Reading) -> None:
    """Extents stated relative to another: "twice as long as it is wide", "three times as long", "half
    as wide as it is long"."""
    n = len(tokens)
    for i, tok in enumerate(tokens):
        if tok.low != "times" and (
            tok.low not in ("twice", "half") or i + 1 >= n or tokens[i + 1].low != "as"
        ):
            continue
        first = i
        if tok.low == "times":
            while first > 0 and tokens[first - 1].tag in ("CD", "NW"):
                first -= 1
            factor = number_value([t.low for t in tokens[first:i]]) if first < i else None
            if factor is None or not 1 < factor <= 20:
                continue
        else:
            factor = 2.0 if tok.low == "twice" else 0.5
        j = i + 1
        if j + 1 >= n or tokens[j].low != "as" or tokens[j + 1].tag not in ("DIM", "DIMN"):
            continue
        role = lx.DIMENSION_WORDS.get(tokens[j + 1].low)
        if role not in lx.LINEAR_ROLES:
            continue
        ref: str | None = None
        last = tokens[j + 1]
        if j + 2 < n and tokens[j + 2].low == "as":
            for t in tokens[j + 3 : j + 7]:
                if t.tag in ("CM", "SEP"):
                    break
                if t.tag in ("DIM", "DIMN"):
                    ref, last = lx.DIMENSION_WORDS.get(t.low), t
                    break
            if ref is None or ref == role:
                continue
        reading.relations.append(_Relation(role, factor, ref, tokens[first].start, last.end))


def _split_hyphen(low: str) -> bool:
    parts = low.split("-")
    if len(parts) == 2 and parts[0] in lx.NUMBER_WORDS and parts[1] in lx.NUMBER_WORDS:
        return False  # "twenty-one"
    return True


def _fix_tags(tokens: list[_Token]) -> list[_Token]:
    """Tags that depend on the neighbours; one linear pass (two for dropped hyphens)."""
    out: list[_Token] = []
    n = len(tokens)
    _tuple_labels(tokens)
    imperial = _imperial_text(tokens)
    letters_w = any(t.low == "w" and t.tag != "LBL" for t in tokens)
    skip_to = -1
    for i, tok in enumerate(tokens):
        prev = out[-1] if out else None
        nxt = tokens[i + 1] if i + 1 < n else None
        prev_num = prev is not None and prev.tag in _NUMBER_TAGS
        tag = tok.tag
        if i < skip_to:
            continue  # the tolerance's own number and unit are dropped
        if (
            tok.low in lx.TOLERANCE_WORDS
            and prev is not None
            and (prev_num or prev.tag in _UNIT_TAGS)
            and nxt is not None
            and nxt.tag in _NUMBER_TAGS
        ):
            j = i + 1
            while j < n and tokens[j].tag in _NUMBER_TAGS:
                j += 1
            if j < n and tokens[j].tag in _UNIT_TAGS | {"IN"}:
                j += 1
            skip_to = j  # "430 g +/- 20 g": a tolerance, not a range or a second value: dropped
            continue
        chained = len(out) >= 2 and out[-2].tag == "DIMN" and len(out[-2].word) == 1  # "L 30 W 20"
        if len(tok.low) == 1 and tok.low in lx.TUPLE_LABELS and tag != "LBL" and (chained or not prev_num):
            k = i + 1
            if k < n and tokens[k].low in ("=", ":"):
                k += 1
            after = tokens[k + 1] if k + 1 < n else None
            if after is not None and after.low == "," and k + 2 < n:
                after = tokens[k + 2]
            if (
                after is not None
                and tokens[k].tag == "CD"
                and (after.tag in ("ULEN", "IN") or (len(after.low) == 1 and after.low in lx.TUPLE_LABELS))
            ):
                # "L 48 cm, dia 28 cm", "L=8cm D=3cm": a letter naming one extent (D is a depth next to a
                # W, else a diameter)
                role = lx.TUPLE_LABELS[tok.low]
                tok.low = "diameter" if role == "depth" and not letters_w else role
                tok.tag = "DIMN"
                out.append(tok)
                continue
        if tag == "RTO" and tok.low in ("-", "–", "—"):
            nxt_unit = nxt is not None and nxt.tag in (_UNIT_TAGS | {"DIM", "DIMN", "HS", "IN"})
            if (prev_num and nxt_unit) or (
                prev is not None and prev.tag in _UNIT_TAGS and nxt is not None and nxt.tag in ("DIM", "DIMN")
            ):
                continue  # "5-cm-long", "10-ish": the hyphen joins, it is not a range
        if tok.low == "." and prev is not None and prev.low in _ABBREVIATIONS:
            if nxt is not None and not nxt.word[:1].isupper():
                continue  # "approx. 5 cm", "3 in. long": an abbreviation, not a sentence end
        if tag == "IN" and prev_num:
            if nxt is None or nxt.low not in lx.DIMENSION_NOUNS or imperial:
                tag = "ULEN"  # "4 in long", "3 in." ; "7 in diameter" stays a preposition, unless the
                # other units are imperial: "1.68 in diameter, 1.62 oz"
        elif tok.low in _SYMBOL_UNITS:
            tag = "ULEN" if prev_num else "CM"
        elif (
            tag in _UNIT_TAGS
            and prev is not None
            and prev.tag in ("HS", "LBL")
            and len(out) >= 2
            and (out[-2].tag in _NUMBER_TAGS)
        ):
            pass  # "250-ish grams", "5H cm"
        elif tag in _UNIT_TAGS and not prev_num and not _number_before_of(out):
            before_a = out[-2] if len(out) >= 2 else None
            if prev is not None and prev.tag == "A" and len(tok.low) > 2:
                if before_a is None or (before_a.tag not in _NUMBER_TAGS and before_a.tag != "OF"):
                    prev.tag = "NW"  # "a liter of water", "about a foot long": "a" is one; not "half a liter"
            elif not (prev is not None and prev.tag == "A"):
                tag = "W"  # "cm" with no number, "m" in "I m", a "cup" of coffee
        elif tag in ("BY", "RTO"):
            nxt_num = nxt is not None and (nxt.tag in _NUMBER_TAGS or nxt.tag in ("A", "HA", "HL", "HU"))
            prev_ok = prev is not None and (prev.tag in _NUMBER_TAGS or prev.tag in _UNIT_TAGS)
            if tag == "BY" and not prev_ok and prev is not None and len(out) >= 2:
                # "7.5 cm long by 5 by 5", "20L x 10W": a labelled value before the sign
                before = out[-2].tag
                prev_ok = (
                    prev.tag in ("DIM", "DIMN") and (before in _UNIT_TAGS or before in _NUMBER_TAGS)
                ) or (prev.tag == "LBL" and before in _NUMBER_TAGS)
            if tag == "BY" and not nxt_num and nxt is not None and nxt.tag == "LBL":
                nxt_num = True  # "x W 10"
            if not (nxt_num and prev_ok):
                tag = "W"
        elif tag == "BETW":
            if nxt is None or nxt.tag not in _NUMBER_TAGS:
                tag = "W"
        elif tag == "AND" and prev is not None and prev.tag in _UNIT_TAGS and nxt is not None:
            after = tokens[i + 2] if i + 2 < n else None
            if nxt.low in lx.FRACTION_WORDS or (
                nxt.tag == "A" and after is not None and after.low in lx.FRACTION_WORDS
            ):
                tag = "UAND"  # "an inch and a half", "a pound and a quarter"
        elif tok.low == "cup" and prev_num:
            tag = "UVOL"  # "1 cup of water"
        elif tok.low == "can" and tag == "SHP":
            if not (
                (prev is not None and prev.low in lx.CAN_PRECEDERS) or (nxt is not None and nxt.low == "of")
            ):
                tag = "W"  # "it can hold": a verb
        elif (
            tag == "DIM"
            and nxt is not None
            and nxt.tag == "HA"
            and i + 2 < n
            and tokens[i + 2].tag in _NUMBER_TAGS
            and not (
                prev_num or (prev is not None and (prev.tag in _UNIT_TAGS or prev.low in ("a", "an", "as")))
            )
            and lx.DIMENSION_WORDS.get(tok.low) in lx.LINEAR_ROLES
        ):
            tag = "DIMN"  # "it is long about 32 cm", "thick maybe 1.5 cm": the word before its value
        elif tag == "MH" and tok.low == "light" and nxt is not None and nxt.low in lx.COLOUR_WORDS:
            tag = "W"
        elif tag == "FRC" and tok.low in lx.ORDINAL_FRACTIONS:
            if not (prev_num or (prev is not None and prev.tag in ("A", "AND"))):
                tag = "W"  # "the top quarter", "third" or "fifth" as an ordinal
        if tag in _UNIT_TAGS and prev_num and _smaller_unit_after(out, tok):
            tag = "USUB"
        tok.tag = tag
        out.append(tok)
    return out


_BY_WORDS = frozenset({"x", "×", "by", "*"})
_IMPERIAL = frozenset({"inch", "foot", "yard", "ounce", "pound", "fluid_ounce"})
_METRIC_LENGTH = frozenset({"millimeter", "centimeter", "meter"})


def _imperial_text(tokens: list[_Token]) -> bool:
    """True when the text's units are imperial (an ounce, pound, inch or foot) and none is a metric
    length: there "7 in diameter" is seven inches."""
    table = unit_table()
    imperial = False
    for tok in tokens:
        if tok.tag in _UNIT_TAGS:
            unit = table.get(tok.low)
            if unit is None:
                continue
            if unit.pint_name in _METRIC_LENGTH:
                return False
            if unit.pint_name in _IMPERIAL:
                imperial = True
    return imperial


def _tuple_labels(tokens: list[_Token]) -> None:
    """Tag LBL the letters that label the numbers of a tuple: "L 20 x W 10 x H 5 cm" (a letter before a
    number, next to a multiplication sign) and "20L x 10W x 5H cm" (a letter glued to its number, before
    a sign or a length unit). "a 2L bottle" keeps its litre."""
    n = len(tokens)
    for i, tok in enumerate(tokens):
        if len(tok.low) != 1 or tok.low not in lx.TUPLE_LABELS:
            continue
        prev = tokens[i - 1] if i else None
        nxt = tokens[i + 1] if i + 1 < n else None
        if prev is not None and prev.tag in _NUMBER_TAGS and prev.end == tok.start:
            if nxt is not None and (nxt.low in _BY_WORDS or nxt.tag == "ULEN"):
                tok.tag = "LBL"
            elif i >= 2 and tokens[i - 2].low in _BY_WORDS and (nxt is None or nxt.tag in ("CM", "SEP")):
                tok.tag = "LBL"
        elif nxt is not None and nxt.tag == "CD" and (prev is None or prev.tag not in _NUMBER_TAGS):
            after = [t.low for t in tokens[i + 2 : i + 4]]
            if (prev is not None and prev.low in _BY_WORDS) or any(w in _BY_WORDS for w in after):
                tok.tag = "LBL"


def _smaller_unit_after(out: list[_Token], tok: _Token) -> bool:
    """True for the second unit of "1 lb 2 oz" / "5 ft 3 in": same kind, smaller, right after the first
    unit and its number."""
    k = len(out) - 1
    while k >= 0 and out[k].tag in _NUMBER_TAGS:
        k -= 1
    if k == len(out) - 1 or k < 1 or out[k].tag not in _UNIT_TAGS or out[k - 1].tag not in _NUMBER_TAGS:
        return False
    table = unit_table()
    first, second = table.get(out[k].low), table.get(tok.low)
    return (
        first is not None
        and second is not None
        and first.kind == second.kind
        and second.factor < first.factor
    )


def _other_object(segment: list[_Token], k: int) -> str | None:
    """For a quantity at ``k`` right after a possessive ("my 2 kg dumbbell", "my old 30 cm ruler"):
    "compared" when its sentence compares or places ("next to", "than", "beside", "heavier"), else
    "owned"; None without a possessive."""
    if not any(t.low in lx.POSSESSIVES for t in segment[max(0, k - 2) : k]):
        return None
    if any(w in lx.COMPARISON_WORDS for t in segment for w in t.low.split()):  # also "lighter than"
        return "compared"
    return "owned"


def _number_before_of(out: list[_Token]) -> bool:
    """True after "<number> of" or "<number> of a": "a couple of kilos", "half of a liter"."""
    k = len(out) - 1
    if k >= 0 and out[k].tag == "A":
        k -= 1
    return k >= 1 and out[k].tag == "OF" and out[k - 1].tag in _NUMBER_TAGS


def _fill_context(segment: list[_Token]) -> int | None:
    """Index in the segment of a contents word ("filled", "full", "contains": anywhere in the sentence;
    "with": before the volume, as "with 500 ml of ..."), or None; a capacity word ("capacity", "empty",
    "can hold") anywhere in the sentence cancels it."""
    found: int | None = None
    for i, tok in enumerate(segment):
        if tok.low in lx.CAPACITY_WORDS:
            return None
        if found is None and tok.low in lx.FILL_WORDS:
            if tok.low in lx.WEAK_FILL_WORDS:
                # "with 500 ml of water": only with "of" after the unit
                if not any(
                    t.low == "of" and segment[j - 1].tag in _UNIT_TAGS
                    for j, t in enumerate(segment[i + 1 :], start=i + 1)
                ):
                    continue
            found = i
    return found


# --------------------------------------------------------------------------------------- small readers
def _size(tree: Tree) -> int:
    """Number of tokens under a chunk."""
    n = 0
    for child in tree:
        n += _size(child) if isinstance(child, Tree) else 1
    return n


def _num(toks: Sequence[_Token]) -> float | None:
    words = [t.low for t in toks]
    if len(words) == 1 and words[0] in ("a", "an"):
        return 1.0
    return number_value(words)


def _hedge_qualifier(toks: Sequence[_Token]) -> str:
    quals = [lx.HEDGES.get(t.low, "about") for t in toks]
    for q in ("at_least", "at_most", "about"):
        if q in quals:
            return q
    return "exact"


def _negated(segment: list[_Token], i: int) -> bool:
    for j in range(i - 1, max(-1, i - 4), -1):
        tag = segment[j].tag
        if segment[j].low in ("or", "nor") and j >= 1 and segment[j - 1].tag in _CATEGORY_TAGS:
            return tag == "NEG" or _negated(segment, j - 1)  # "not made of glass or ceramic"
        if tag in ("CM", "SEP", "AND"):
            return False
        if tag == "NEG":
            return True
    return False


def _in_part_phrase(segment: list[_Token], i: int, through_and: bool = False) -> bool:
    """True when the word at ``i`` describes a part or a container, not the object: a part noun follows it
    ("rubber grip", "plastic bag", "long stem") or it is in a phrase opened by "with"/"in"/"on" ("with a
    rubber grip", "in a tin cup"; a comma, a sentence end or, unless ``through_and``, "and" closes the
    phrase: a material after "and" may be the object's, a shape noun after "and" is still a part)."""
    if i + 1 < len(segment) and segment[i + 1].low in lx.PART_NOUNS:
        return True
    for j in range(i - 1, max(-1, i - (7 if through_and else 4)), -1):
        t = segment[j]
        if t.tag in ("CM", "SEP") or (t.tag == "AND" and not through_and):
            return False
        if t.low in lx.PART_PREPOSITIONS and segment[j + 1].tag not in ("DIM", "DIMN", *_NUMBER_TAGS):
            return True  # not "7 cm in diameter and round", "with 500 ml"
    return False


def _material_rank(segment: list[_Token], i: int) -> int:
    """2: the object's own material ("made of X", "X body", "the body is X"); 0: a part's ("with a
    rubber grip"); 1: any other mention."""
    if i >= 2 and segment[i - 1].low in ("of", "from"):
        if segment[i - 2].low in ("made", "out", "built", "constructed", "consists"):
            return 2  # "made of plastic" beats a material in a name
    if i + 1 < len(segment) and segment[i + 1].low in lx.BODY_WORDS:
        return 2  # "a plastic body", "clear plastic barrel"
    for j in range(i - 1, max(-1, i - 4), -1):
        if segment[j].low in lx.BODY_WORDS:
            return 2  # "the body is aluminium", "body: steel"
        if segment[j].tag in ("CM", "SEP", "AND"):
            break
    return 0 if _in_part_phrase(segment, i) else 1


def _read_categories(segment: list[_Token], base: int, reading: _Reading) -> None:
    n = len(segment)
    for i, tok in enumerate(segment):
        pos = base + i
        tag = tok.tag
        nxt = segment[i + 1].low if i + 1 < n else ""
        if tag not in _NUMBER_TAGS and not (tok.low == "can" and tag != "SHP"):
            if nxt in lx.BALL_COMPOUND_HEADS and (
                tok.low in lx.SPHERE_WORDS or tok.low.endswith(lx.BALL_SUFFIX)
            ):
                pass  # "baseball cap", "ball bearing": not a ball
            elif tok.low in lx.VESSEL_WORDS and i and segment[i - 1].low in ("the", "its", "at"):
                pass  # "wide at the bowl": a part
            else:
                reading.cue_words.add(tok.low)
                if tok.low.endswith(lx.BALL_SUFFIX) and len(tok.low) > len(lx.BALL_SUFFIX):
                    reading.cue_words.add(lx.BALL_SUFFIX)  # "softball", "basketball"
        if tag == "MH":
            hint = lx.MASS_HINT_WORDS[tok.low]
            if _negated(segment, i):
                hint = "heavy" if hint == "light" else "light"
            reading.mass_hints.append(hint)
            continue
        if tag == "DIM" and tok.low in ("long", "elongated") and pos not in reading.in_dim_chunk:
            if any(t.low == "as" for t in segment[max(0, i - 3) : i]):
                continue  # "twice as long as it is wide": a proportion, not a long shape
            if _in_part_phrase(segment, i, True):
                continue  # "with a long stem", "a long handle": a part is long
            feature, value, rank = "shape", "long", 2
        elif tag in _CATEGORY_TAGS:
            feature = _CATEGORY_TAGS[tag]
            if feature == "shape":
                value, rank = lx.SHAPE_WORDS[tok.low]
                if nxt in lx.MODIFIED_HEADS and tok.low not in lx.MODIFIED_HEADS:
                    continue  # "bottle opener", "pen holder": the shape of something else
                if tok.low == "thin" and i + 1 < n and segment[i + 1].tag == "MAT":
                    continue  # "thin plastic", "thin glass": the wall, not the object's shape
                if nxt == "of" and tok.low in lx.MEASURE_NOUNS:
                    continue  # "a bar of soap"
                if (nxt == "of" and tok.low in lx.CONTAINER_NOUNS) or _in_part_phrase(segment, i, True):
                    rank = 0  # "a bar of soap", "with a long stem", "in a tin cup"
            else:
                table = lx.TABLES[feature]
                value = table[tok.low]
                rank = _material_rank(segment, i) if feature == "material" else 1
                if feature in ("texture", "fragility") and i >= 1 and segment[i - 1].low in lx.MEDIUM_WORDS:
                    value = "medium"
        elif tok.low in lx.MEDIUM_WORDS and i + 1 < len(segment):
            nxt = segment[i + 1].low
            if nxt in ("texture", "surface", "roughness", "finish"):
                feature, value, rank = "texture", "medium", 1
            elif nxt in ("fragility", "fragile", "strength"):
                feature, value, rank = "fragility", "medium", 1
            else:
                continue
        else:
            continue
        if _negated(segment, i):
            if feature == "fragility":
                value = lx.NEGATED_FRAGILITY[value]
            else:
                continue
        reading.categories.setdefault(feature, []).append((rank, pos, value, tok))


# ------------------------------------------------------------------------------------------ resolution
def _resolve(
    reading: _Reading, tokens: list[_Token], text: str
) -> tuple[dict[str, FeatureEvidence], str | None]:
    features: dict[str, FeatureEvidence] = {}
    _resolve_dims(reading, text, features)
    _resolve_mass(reading, text, features)
    for feature, cands in reading.categories.items():
        best = max(cands, key=lambda c: (c[0], -c[1]))
        _rank, _pos, value, tok = best
        features[feature] = FeatureEvidence(feature, value, "exact", None, None, tok.word, tok.start, tok.end)
    hint = reading.mass_hints[0] if reading.mass_hints else None
    ordered = {f: features[f] for f in FEATURES if f in features}
    return ordered, hint


def _unit_for(q: _Quantity, reading: _Reading) -> Unit | None:
    """The quantity's own unit, else the nearest length unit before it, else after it, else cm."""
    if q.unit is not None:
        return q.unit
    before = [u for p, u in reading.length_units if p < q.pos]
    if before:
        return before[-1]
    after = [u for p, u in reading.length_units if p > q.pos]
    if after:
        return after[0]
    return unit_table()["cm"]


@dataclass
class _Dim:
    value: float
    low: float | None
    high: float | None
    qualifier: str
    start: int
    end: int


def _to_cm(q: _Quantity, reading: _Reading, stmt: _DimStatement, scale: float = 1.0) -> _Dim | None:
    unit = _unit_for(q, reading)
    if unit is None or unit.kind != "length":
        return None
    f = unit.factor * scale
    value = q.value * f
    if not 0 < value <= MAX_DIM_CM:
        return None
    return _Dim(
        value,
        None if q.low is None else q.low * f,
        None if q.high is None else q.high * f,
        q.qualifier,
        stmt.start,
        stmt.end,
    )


def _resolve_dims(reading: _Reading, text: str, features: dict[str, FeatureEvidence]) -> None:
    """Assign the stated extents to a >= b >= c (rules in recall/PARSER.md, "Dimensions")."""
    cues = reading.cue_words
    cube = bool(cues & lx.CUBE_WORDS)
    sphere = bool(cues & lx.SPHERE_WORDS)
    cylinder = bool(cues & lx.CYLINDER_WORDS)
    disc = bool(cues & lx.DISC_WORDS)
    flat = bool(cues & lx.FLAT_WORDS)
    rod = bool(cues & lx.ROD_WORDS) and not flat and not disc
    round_cue = sphere or cylinder or bool(cues & (lx.ROUND_WORDS | (lx.DISC_WORDS - {"flat", "cap"})))
    slots: dict[str, _Dim] = {}
    abc = ("a_cm", "b_cm", "c_cm")

    def put(names: Sequence[str], dims: Sequence[_Dim]) -> None:
        ordered = sorted(dims, key=lambda d: -d.value)
        for name, dim in zip(names, ordered, strict=False):
            slots[name] = dim

    for rel in reading.relations:  # "twice as long as it is wide, 11 cm wide": 22 cm long
        if any(st.role == rel.role for st in reading.dims):
            continue
        if rel.ref is not None:
            source = next((st for st in reading.dims if st.role == rel.ref), None)
        else:
            source = next((st for st in reversed(reading.dims) if st.start < rel.start), None)
        if source is None or source.role == rel.role:
            continue
        q = source.quantities[0]
        derived = replace(
            q, value=q.value * rel.factor, low=None, high=None, qualifier="about", unit=_unit_for(q, reading)
        )
        reading.dims.append(_DimStatement(rel.role, [derived], rel.start, rel.end))
    by_role: dict[str, _Dim] = {}
    stated_width = any(stmt.role == "width" for stmt in reading.dims)  # "65 cm across and 20 cm wide"
    for stmt in reading.dims:
        role = stmt.role
        if role == "radius":
            role = "diameter"
        elif role == "across":
            role = "diameter" if round_cue or stated_width else "width"
        if role in by_role:
            continue
        dim = _to_cm(stmt.quantities[0], reading, stmt, 2.0 if stmt.role == "radius" else 1.0)
        if dim is not None:
            by_role[role] = dim
    three = bool(by_role.keys() & {"length", "height", "overall"}) and bool(
        by_role.keys() & {"thickness", "depth"}
    )
    if round_cue and not flat and "diameter" not in by_role and "width" in by_role and not three:
        by_role["diameter"] = by_role.pop("width")  # "a mug 8 cm wide": the width of a round thing
    if "overall" in by_role and "length" in by_role:
        del by_role["length"]  # "the blade is 20 cm long, 33 cm overall": the length of a part
    linear = [(by_role[r], r) for r in lx.LINEAR_ROLES if r in by_role]
    linear.sort(key=lambda dr: dr[0].start)
    multi = None
    if reading.multis:
        stmt = reading.multis[0]
        multi = [d for q in stmt.quantities if (d := _to_cm(q, reading, stmt)) is not None]
        if multi and multi[0].qualifier == "about":  # "roughly 9.5 x 6 x 3.5 inches": the hedge covers all
            for d in multi[1:]:
                if d.qualifier == "exact":
                    d.qualifier = "about"
        if len(multi) < 2 or (len(multi) == 2 and len(linear) >= 3):
            multi = None  # three labelled extents say more than a pair
    if multi is not None:
        if len(multi) == 2:
            # "21 x 15 cm, 1 cm thick", "23 cm tall, 7 x 7 cm base": a labelled third extent
            for role in ("thickness", "depth", "height", "length", "overall", "width"):
                extra = by_role.get(role)
                if extra is not None and not any(abs(extra.value - d.value) <= 0.02 * d.value for d in multi):
                    multi.append(extra)
                    break
        put(abc, multi[:3])
    elif "side" in by_role:
        side = by_role["side"]
        put(abc, [side, side, side])
    elif "diameter" in by_role or "square" in by_role:
        # a diameter or a square cross-section: two equal extents
        diameter = by_role.get("diameter") or by_role["square"]
        others = [d for d, _r in linear]
        if len(others) >= 2:  # a pan 28 across, 48 long with the handle, 5 deep: 48, 28, 5
            put(abc, [diameter, others[0], others[1]])
        elif others:
            put(abc, [diameter, diameter, others[0]])
        elif sphere and "diameter" in by_role:
            put(abc, [diameter, diameter, diameter])
        elif cylinder and not disc and "diameter" in by_role:
            put(("b_cm", "c_cm"), [diameter, diameter])
        else:
            put(("a_cm", "b_cm"), [diameter, diameter])
    elif linear:
        if len(linear) == 1 and (cube or sphere):
            d = linear[0][0]
            put(abc, [d, d, d])
        elif len(linear) >= 3:
            put(abc, [d for d, _r in linear[:3]])
        elif len(linear) == 2:
            roles = {r for _d, r in linear}
            names: tuple[str, ...]
            values = [d for d, _r in linear]
            if roles in ({"length", "thickness"}, {"overall", "thickness"}) and rod:
                values = sorted(values, key=lambda d: -d.value)
                values.append(values[1])  # "a pencil 19 cm long and 7 mm thick": round, b = c
                names = abc
            elif "thickness" in roles:
                names = ("a_cm", "c_cm") if roles & {"length", "height", "overall"} else ("b_cm", "c_cm")
            else:
                names = ("a_cm", "b_cm")
            put(names, values)
        else:
            d, role = linear[0]
            slot = {"length": "a_cm", "height": "a_cm", "overall": "a_cm", "width": "b_cm", "depth": "b_cm",
                    "thickness": "c_cm"}  # fmt: skip
            put([slot[role]], [d])
    elif reading.sizes:
        sizes = [d for stmt in reading.sizes[:3] if (d := _to_cm(stmt.quantities[0], reading, stmt))]
        if len(sizes) == 1 and (cube or sphere):
            put(abc, sizes * 3)
        else:
            put(abc, sizes)
    for name, dim in slots.items():
        features[name] = FeatureEvidence(
            name, round(dim.value, 4), dim.qualifier, _r(dim.low), _r(dim.high), text[dim.start : dim.end],
            dim.start, dim.end,
        )  # fmt: skip


def _r(value: float | None) -> float | None:
    return None if value is None else round(value, 4)


def _resolve_mass(reading: _Reading, text: str, features: dict[str, FeatureEvidence]) -> None:
    masses = reading.masses or [(q, False) for q in reading.other_masses]
    for q, in_contents in masses:
        assert q.unit is not None
        grams = q.value * q.unit.factor
        if not 0 < grams <= MAX_MASS_G:
            continue
        qualifier = "at_least" if in_contents and q.qualifier != "range" else q.qualifier
        f = q.unit.factor
        low = grams if qualifier == "at_least" else (None if q.low is None else q.low * f)
        high = None if q.high is None or qualifier == "at_least" else q.high * f
        features["mass_g"] = FeatureEvidence(
            "mass_g", round(grams, 4), qualifier, _r(low), _r(high), text[q.start : q.end], q.start, q.end
        )
        return
    for q in reading.contents:
        assert q.unit is not None
        grams = q.value * q.unit.factor * lx.CONTENTS_DENSITY_G_PER_ML
        if not 0 < grams <= MAX_MASS_G:
            continue
        features["mass_g"] = FeatureEvidence(
            "mass_g",
            round(grams, 4),
            "at_least",
            round(grams, 4),
            None,
            text[q.start : q.end],
            q.start,
            q.end,
        )
        return


# ------------------------------------------------------------------------------------------ module API
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
