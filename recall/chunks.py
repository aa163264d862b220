"""Stage 3 of the description parser (the paper's Fig. 2): tags to chunks.

A cascaded ``nltk.chunk.RegexpParser`` over :data:`GRAMMAR` (one stage per label, in order) builds
NUM, UNIT, HEDGE, RANGE, SUB, QUANT, MULTI and DIM chunks, one sentence at a time. Sentences end at
``SEP`` tokens and are cut every :data:`MAX_SEGMENT_TOKENS` tokens, which bounds the regular
expressions' work (no catastrophic backtracking on long or hostile input). A stage runs only when the
tags it needs are present, a rule only when its required tags are.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from typing import Any

from recall.tags import NUMBER_TAGS, UNIT_TAGS
from recall.tokens import Token
from recall.toolkit import ChunkString, RegexpChunkParser, RegexpParser, Tree

__all__ = ["GRAMMAR", "MAX_SEGMENT_TOKENS", "Chunker", "size"]

#: A sentence longer than this many tokens is chunked in pieces of this size.
MAX_SEGMENT_TOKENS = 48

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
  {<QUANT><DIM|DIMN>?<BY><QUANT><DIM|DIMN>?<BY><QUANT><DIM|DIMN>?(<BY><QUANT><DIM|DIMN>?)+}
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
        # standard engine, for the reason given in recall.tokens: the grammar is a tested constant and a
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


#: Tags worth chunking a sentence for; a sentence without any is left flat.
_INTERESTING = NUMBER_TAGS | UNIT_TAGS | {"DIM", "DIMN", "MAT", "SHP", "RIG", "TEX", "FRA", "MH"}


class Chunker:
    """The cascade over :data:`GRAMMAR`, built once; thread-safe."""

    def __init__(self) -> None:
        self._cascade = _Cascade(GRAMMAR)

    @staticmethod
    def segments(tokens: list[Token]) -> Iterator[list[Token]]:
        """The sentences of the tagged tokens, each at most :data:`MAX_SEGMENT_TOKENS` long."""
        seg: list[Token] = []
        for tok in tokens:
            seg.append(tok)
            if tok.tag == "SEP" or len(seg) >= MAX_SEGMENT_TOKENS:
                yield seg
                seg = []
        if seg:
            yield seg

    def chunk(self, segment: list[Token]) -> Tree:
        """One sentence's chunk tree (flat when it has nothing worth chunking)."""
        pairs = [(t.word, t.tag) for t in segment]
        if not any(t.tag in _INTERESTING for t in segment):
            return Tree("S", pairs)
        try:
            return self._cascade.parse(pairs)
        except (TimeoutError, ValueError, RecursionError):  # nltk.redos backstop; never expected
            return Tree("S", pairs)


def size(tree: Tree) -> int:
    """Number of tokens under a chunk."""
    n = 0
    for child in tree:
        n += size(child) if isinstance(child, Tree) else 1
    return n
