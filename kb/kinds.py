"""Object kinds: a small hierarchy of what household things are, and the nouns that name each kind.

Two data files, read once:

* ``kb/data/kinds.csv`` (``kind,parent,description``): the hierarchy, rooted at ``object`` (fruit ->
  food -> object; cup -> container -> object; ...). Depth two or three; documented in ``recall/RECALL.md``.
* ``kb/data/kind_nouns.csv`` (``noun,kind,lang,english``): household nouns (one or more words, singular)
  with their kind, their language and, when it differs from the noun, the English name a catalog would
  use ("spanner" -> wrench, "caffettiera" (it) -> moka pot, "Wasserkocher" (de) -> electric kettle).

Every seed catalog object has a kind (:func:`kind_of_name`; a test checks completeness), and so does
every noun. The recall uses kinds to say that a described noun is **not in the catalog** and to find the
closest catalog objects of the same kind; ingestion uses :func:`assign_kind` to give a store's object in
another language a kind and an English alias, with where it came from.
"""

from __future__ import annotations

import csv
import dataclasses
import functools
import re
import unicodedata
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

from kb.errors import ObjrecallError

__all__ = [
    "IMITATION_WORDS",
    "KindAssignment",
    "Kind",
    "Noun",
    "ancestors",
    "assign_kind",
    "kind_of_name",
    "kinds",
    "noun_in",
    "nouns",
    "singular",
    "title_words",
    "words_of",
]

_DATA = Path(__file__).resolve().parent / "data"
ROOT = "object"
#: A name with one of these words before a food noun is a toy ("plastic banana", "toy apple").
IMITATION_WORDS = frozenset({"plastic", "toy", "fake", "play", "wooden", "wood", "felt", "rubber"})


@dataclass(frozen=True)
class Kind:
    name: str
    parent: str | None
    description: str


@dataclass(frozen=True)
class Noun:
    """A noun of the lexicon: its words (singular, lower case), kind, language and English name."""

    words: tuple[str, ...]
    kind: str
    lang: str
    english: str

    @property
    def text(self) -> str:
        return " ".join(self.words)


# ----------------------------------------------------------------------------------------------- words
_WORD = re.compile(r"[^\W_]+")
#: Irregular plurals ("dice" is the plural of "die").
_IRREGULAR = {"dice": "die", "knives": "knife", "leaves": "leaf", "loaves": "loaf", "halves": "half",
              "mice": "mouse", "teeth": "tooth", "shelves": "shelf", "tongs": "tongs"}  # fmt: skip


def singular(word: str) -> str:
    """An English plural made singular by its spelling ("boxes" -> box, "batteries" -> battery)."""
    if word in _IRREGULAR:
        return _IRREGULAR[word]
    if len(word) <= 3 or word.endswith(("ss", "us", "is")):
        return word
    if word.endswith("ies") and len(word) > 4:
        return word[:-3] + "y"
    if word.endswith(("ches", "shes", "xes", "zes", "sses")):
        return word[:-2]
    if word.endswith("s"):
        return word[:-1]
    return word


def words_of(text: str) -> list[str]:
    """Lower-case word tokens, apostrophes dropped (rubik's -> rubiks), hyphens split, plurals singular.
    Letters of any script count ("théière", "löffel")."""
    text = text.lower().replace("'", "").replace("\u2019", "")
    return [singular(w) for w in _WORD.findall(text)]


def _fold(word: str) -> str:
    """A word without accents ("théière" -> "theiere"), for store titles typed either way."""
    return "".join(c for c in unicodedata.normalize("NFKD", word) if not unicodedata.combining(c))


# ------------------------------------------------------------------------------------------------ data
@functools.cache
def kinds() -> dict[str, Kind]:
    """The kind hierarchy (``kb/data/kinds.csv``), by name."""
    out: dict[str, Kind] = {}
    with (_DATA / "kinds.csv").open(encoding="utf-8", newline="") as fh:
        for row in csv.DictReader(fh):
            out[row["kind"]] = Kind(row["kind"], row["parent"] or None, row["description"])
    for kind in out.values():
        if kind.parent is not None and kind.parent not in out:
            raise ObjrecallError(f"kinds.csv: kind {kind.name!r} has unknown parent {kind.parent!r}")
    return out


@functools.cache
def nouns() -> dict[tuple[str, ...], Noun]:
    """The noun lexicon (``kb/data/kind_nouns.csv``), keyed by its words (accents folded too)."""
    table = kinds()
    out: dict[tuple[str, ...], Noun] = {}
    with (_DATA / "kind_nouns.csv").open(encoding="utf-8", newline="") as fh:
        for row in csv.DictReader(fh):
            words = tuple(words_of(row["noun"]))
            if row["kind"] not in table:
                raise ObjrecallError(f"kind_nouns.csv: noun {row['noun']!r} has unknown kind {row['kind']!r}")
            noun = Noun(words, row["kind"], row["lang"], row["english"] or row["noun"])
            out.setdefault(words, noun)
            if not row["noun"].isascii():  # an ASCII word is its own folded form
                out.setdefault(tuple(_fold(w) for w in words), noun)
    return out


@functools.cache
def _longest() -> int:
    return max(len(k) for k in nouns())


def ancestors(kind: str) -> list[str]:
    """The kind and its ancestors up to the root: "fruit" -> ["fruit", "food", "object"]."""
    table = kinds()
    out = []
    while kind is not None and kind in table and kind not in out:
        out.append(kind)
        kind = table[kind].parent
    return out


# ----------------------------------------------------------------------------------------------- nouns
def noun_in(words: Sequence[str], *, head_last: bool = True) -> Noun | None:
    """The lexicon noun that heads ``words`` (normalised words of a name or phrase).

    English (``head_last``): the longest lexicon phrase ending at the head, the word before "of" when
    there is one ("bottle of water"), else the last word ("tomato soup can" -> can). Otherwise (store
    titles in any language) the longest lexicon phrase anywhere, leftmost first ("caffettiera moka in
    alluminio" -> caffettiera)."""
    words = [w for w in words if w]
    if not words:
        return None
    table = nouns()
    if head_last:
        end = words.index("of", 1) if "of" in words[1:] else len(words)
        for n in range(min(_longest(), end), 0, -1):
            key = tuple(words[end - n : end])
            if key in table:
                return table[key]
        return None
    folded = [_fold(w) for w in words]
    for n in range(min(_longest(), len(words)), 0, -1):
        for i in range(len(words) - n + 1):
            for seq in (words, folded):
                key = tuple(seq[i : i + n])
                if key in table:
                    return table[key]
    return None


def kind_of_name(name: str, aliases: Iterable[str] = ()) -> str | None:
    """The kind of a catalog object from its name, else its aliases: the kind of the head noun; a food
    noun after an imitation word ("plastic banana") is a toy. None when no name has a lexicon noun."""
    for phrase in (name, *aliases):
        words = words_of(phrase)
        noun = noun_in(words)
        if noun is None:
            continue
        if "food" in ancestors(noun.kind) and any(w in IMITATION_WORDS for w in words):
            return "toy"
        return noun.kind
    return None


# ------------------------------------------------------------------------------------------- ingestion
@dataclass(frozen=True)
class KindAssignment:
    """A kind and an English alias for a stored object, with where they came from: ``provenance`` is
    ``"title"``, ``"breadcrumb: <text>"`` or ``"category: <text>"`` plus the lexicon noun used."""

    kind: str
    english: str | None
    noun: str
    lang: str
    provenance: str


def assign_kind(
    title: str, *, breadcrumbs: Sequence[str] = (), categories: Sequence[str] = ()
) -> KindAssignment | None:
    """Kind and English alias of a store's object, from its title (any language of the lexicon) and
    its category trail: the page's JSON-LD ``category`` values, then its breadcrumbs (most specific, i.e.
    last, first). The title's model names and brands never make a kind (:func:`title_words`: "APPLE
    iMac", "»K 3 Full Control«"). When the title's kind and the trail's disagree (neither is the other's
    ancestor), the trail wins: it is the store's own filing. The English alias is given only when the noun
    found is not English or has another English name ("caffettiera moka in alluminio 3 tazze" -> jug,
    "moka pot"). None when nothing is recognised."""
    own = _assigned("title", title_words(title), head_last=True)
    trail = [(f"category: {c}", c) for c in categories]
    trail += [(f"breadcrumb: {b}", b) for b in reversed(list(breadcrumbs))]
    filed = next(
        (got for where, text in trail if text and text.strip() for got in [_assigned(where, words_of(text))] if got),
        None,
    )
    if own is None or filed is None:
        return own or filed
    if own.kind in ancestors(filed.kind) or filed.kind in ancestors(own.kind):
        return own
    return dataclasses.replace(filed, provenance=f"{filed.provenance}, over the title's {own.noun!r}")


def _assigned(where: str, words: list[str], head_last: bool = False) -> KindAssignment | None:
    """The kind a text's words name (an English head noun when ``head_last`` finds one, else the longest
    lexicon noun anywhere), with ``where`` as provenance; None when none."""
    noun = noun_in(words) if head_last else None
    if noun is None or noun.lang != "en":
        noun = noun_in(words, head_last=False) or noun
    if noun is None:
        return None
    english = noun.english if (noun.lang != "en" or noun.english != noun.text) else None
    return KindAssignment(noun.kind, english, noun.text, noun.lang, f"{where} ({noun.text!r}, {noun.lang})")


#: Text in quotation marks in a store title: a model or series name ("Hochdruckreiniger »K 3 Full
#: Control«", "Lampe \u201eHalo\u201c").
_QUOTED = re.compile(r"[«»\u201c\u201d\u201e\"][^«»\u201c\u201d\u201e\"]*[«»\u201c\u201d\u201e\"]")


def title_words(title: str) -> list[str]:
    """A store title's words (:func:`words_of`) without its model names and brands: text in quotation
    marks, and, when the title has other words too, words of two or more capital letters
    ("APPLE iMac Pro", "KÄRCHER", "WELEDA Citrus"). A brand that is also a noun thus makes no kind."""
    text = _QUOTED.sub(" ", title or "")
    tokens = _WORD.findall(text)
    if any(t.isalpha() and not t.isupper() for t in tokens):
        text = _WORD.sub(lambda m: " " if len(m.group()) > 1 and m.group().isalpha() and m.group().isupper() else m.group(), text)
    return words_of(text)
