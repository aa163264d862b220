"""The subject of a description: its first noun phrase, and which words can head one.

:func:`subject_phrase` finds the description's subject noun phrase without a part-of-speech tagger ("A
plush dinosaur toy, 35 cm" -> plush dinosaur toy); :func:`feature_words` and
:func:`adjective_feature_words` are the parser-lexicon words that state a feature rather than name an
object, so that the name index and the open set can tell a noun from a feature word. A heuristic, used
only as evidence (``recall/RECALL.md``, "Unknown subject noun").
"""

from __future__ import annotations

import functools
import re
from collections.abc import Sequence

from kb.kinds import singular, words_of
from recall.negated_nouns import _negations, _phrase_negation, negated_spans, negated_words
from recall.word_classes import adjective_feature_words, feature_words, is_adjective, is_participle

__all__ = [
    "adjective_feature_words",
    "counted_head",
    "said_in_plural",
    "feature_words",
    "is_adjective",
    "is_participle",
    "negated_spans",
    "negated_words",
    "noun_phrase",
    "subject_head",
    "subject_phrase",
]

_WORD = re.compile(r"[^\W_]+")

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
#: An article before a request word makes it a noun ("a *can* of WD-40", "the *pick* of the bunch").
_ARTICLES = frozenset({"a", "an", "the"})
#: A past participle ("shaped", "filled", "covered"), which after the head noun and before a function word
#: ends the subject phrase.
_ADJECTIVE_PARTICIPLE = re.compile(r"..ed$")
#: Verbs of measuring that also make compound nouns ("a glass *measuring* cup", "a *weighing* scale").
_COMPOUND_VERBS = frozenset({"measuring", "weighing"})
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
    return next(_phrases(text), ())


def _phrases(text: str):
    """The noun phrases of the first sentence, one per chunk (see :func:`subject_phrase`), in order; a
    negated phrase is none ("not a mug, a glass": glass), and when every phrase of the first sentence is
    negated, the next sentence's ("Not a mug. A glass.")."""
    low = text.lower().replace("\u2019", "'")
    low = re.sub(r"\b(it|that|there|what|he|she)'s\b", r"\1 is", low).replace("'s", "").replace("'", "")
    sentences = re.split(r"[.!?;\n]", low, maxsplit=2)  # a colon ends a chunk: "..., 8 cm tall: a salt shaker"
    found = False
    for n, sentence in enumerate(sentences[:2]):
        for phrase in _sentence_phrases(sentence):
            found = True
            yield phrase
        if found or n or not _phrase_negation().search(sentence):
            return


_LETTER_HYPHEN = re.compile(r"([^\W\d_]+)-(?=[^\W\d_])")


def _joined(m: re.Match[str]) -> str:
    """A word and its hyphen as one phrase's words, but a number word ("a *two*-slice toaster") keeps the
    hyphen: it states a count, skipped like any number."""
    from recall import lexicon as lx

    word = m.group(1)
    return f"{word}-" if word in lx.NUMBER_WORDS else f"{word} "


def _sentence_phrases(sentence: str):
    """The noun phrases of one sentence (lower case, apostrophes dropped), one per chunk. A hyphen between
    letters joins the words of one phrase ("a *cross-head* screwdriver", "a t-shirt"), as the catalog's
    names are read (:func:`kb.kinds.words_of`); any other hyphen (a range, a dash) ends a chunk."""
    sentence = _LETTER_HYPHEN.sub(_joined, sentence)
    for chunk in re.split(r"[,:()\[\]\d\"/&+*=-]", sentence):
        phrase: list[str] = []
        previous = ""
        counted = False
        words = _WORD.findall(chunk)
        negated = negated_words(words)
        for i, word in enumerate(words):
            if i in negated or word in _negations():
                if phrase:
                    break  # "a mug not a glass"
            elif not phrase and previous not in _ARTICLES and _request_word(word, words[i + 1 : i + 2]):
                pass  # "Could you pass the salt shaker", "Where is the scoop", "Hand me the hammer"
            elif (word in _PHRASE_ENDS or _size_words(words, i)) and not (
                phrase and _compound_verb(word, words[i + 1 : i + 2])
            ):
                if phrase:
                    break
            elif phrase and _ADJECTIVE_PARTICIPLE.search(word) and set(words[i + 1 : i + 2]) & _PHRASE_ENDS:
                break  # "a kitchen timer *shaped* like a tomato", "a tin *filled* with buttons"
            elif previous in _PRONOUNS:  # "i found this ...": the word after a pronoun is its verb
                pass
            elif not phrase and previous == "of" and word in _material_words():
                pass  # "made of glass, ...": a material, not the subject
            elif word not in _PHRASE_SKIP:
                counted = counted or (not phrase and previous in ("a", "an"))
                phrase.append(word)
            previous = word
        if phrase and not all(w in _amount_words() for w in phrase):  # "A two-slice toaster": past the "two"
            yield tuple(singular(w) for w in phrase)
        elif counted and len(phrase) == 1 and _hedge_start_only(phrase[0]):
            yield (singular(phrase[0]),)  # "a lighter, 20 g": no "than" follows, an article counts it


def counted_head(text: str) -> str | None:
    """The subject's head noun when an indefinite article counts it ("*a* glass", "*a* tall glass, 12 cm",
    "*a* glass of water"), else None. A material word so counted names a thing ("a glass": the drinking
    glass), not what a thing is made of ("glass, 10 cm tall"; "a glass bottle", whose head is "bottle";
    "a glass and steel lamp", "a glass-topped table": a material joined to another word)."""
    phrase = subject_phrase(text)
    if not phrase:
        return None
    low = text.lower()
    skip = "|".join(sorted(_PHRASE_SKIP))
    words = r"\s+".join(re.escape(w) for w in phrase)
    counted = rf"\b(?:a|an|one)\s+(?:(?:{skip})\s+)*{words}\b(?!\s*[-/&+]|\s+(?:and|or|n)\b)"
    return phrase[-1] if re.search(counted, low) else None


















def noun_phrase(text: str) -> tuple[str, ...]:
    """The subject phrase (:func:`subject_phrase`), or, when its words only state features ("Steel, 15
    cm long, a nutcracker": "steel"), the first later phrase of the sentence that ends in a noun of the
    kinds lexicon (:func:`kb.kinds.noun_in`) introduced by a determiner (:func:`introduced`); the subject
    phrase otherwise."""
    from kb.kinds import noun_in

    phrases = _phrases(text)
    first = next(phrases, ())
    if first and not all(w in feature_words() for w in first):
        return first
    # a later phrase names the object only when a determiner introduces it ("a nutcracker"; not "tiny,
    # two screw caps" or "plastic, handset on a base": parts of the object described)
    return next((p for p in phrases if noun_in(list(p)) is not None and introduced(text, p[-1])), first)


#: Words of a request or question before the subject ("please", "could you", "where is", "find me",
#: "looking for"): skipped before the subject phrase starts, when a function word, pronoun or
#: determiner follows them ("*hand* me the hammer"; not "a *hand* towel": a noun follows).
_REQUEST_WORDS = frozenset(
    "please can could would will find get grab bring hand pass give fetch show locate pick need want where "
    "what which looking look search searching seeking got".split()
)


def _size_words(words: list[str], i: int) -> bool:
    """Whether ``words[i]`` starts the statement of a size, never a word of the subject: a hedge of the
    parser's lexicon ("about", "approximately", "up to", "a bit over", "bigger than"; ``lexicon.HEDGES``),
    a range word ("between", "from") or a dimension noun that ends its chunk or comes before a phrase
    end ("a ball diameter 6 cm", "a box height is 10 cm"; not "a side table")."""
    single, sequences, dimension_nouns = _size_vocabulary()
    word = words[i]
    if word in single or any(tuple(words[i : i + len(seq)]) == seq for seq in sequences.get(word, ())):
        return True
    return word in dimension_nouns and (i + 1 == len(words) or words[i + 1] in _PHRASE_ENDS)


@functools.cache
def _size_vocabulary() -> tuple[frozenset[str], dict[str, list[tuple[str, ...]]], frozenset[str]]:
    """The single-word hedges and range words, the multi-word hedges by their first word, and the
    one-word dimension nouns (see :func:`_size_words`)."""
    from recall import lexicon as lx

    single = {h for h in lx.HEDGES if " " not in h} | {w for w, t in lx.FUNCTION_WORDS.items() if t == "BETW"}
    sequences: dict[str, list[tuple[str, ...]]] = {}
    for hedge in lx.HEDGES:
        words = tuple(_WORD.findall(hedge))
        if len(words) > 1:
            sequences.setdefault(words[0], []).append(words)
    nouns = frozenset(w for w in lx.DIMENSION_NOUNS if " " not in w)
    return frozenset(single), sequences, nouns


def _request_word(word: str, following: list[str]) -> bool:
    if word == "please":
        return True
    if word not in _REQUEST_WORDS or not following:
        return False
    return following[0] in _PHRASE_ENDS or following[0] in _PHRASE_SKIP


def _compound_verb(word: str, following: list[str]) -> bool:
    """Whether ``word`` is the first part of a compound noun, not the phrase's verb: "measuring" or
    "weighing" followed by a word that is no function word, number or hedge ("a
    measuring cup"; not "a box measuring about ..." or "measuring twelve inches")."""
    if word not in _COMPOUND_VERBS or not following:
        return False
    nxt = following[0]
    return nxt not in _PHRASE_ENDS and nxt not in _PHRASE_SKIP and nxt not in _amount_words()


@functools.cache
def _material_words() -> frozenset[str]:
    from recall.lexicon import MATERIAL_WORDS

    return frozenset(w for w in MATERIAL_WORDS if " " not in w)


@functools.cache
def _amount_words() -> frozenset[str]:
    """Words that start an amount after a verb of measuring: numbers, fractions, hedges ("twelve",
    "half", "roughly")."""
    from recall import lexicon as lx

    tables = (lx.NUMBER_WORDS, lx.MAGNITUDE_WORDS, lx.FRACTION_WORDS, lx.HEDGES)
    return frozenset(w for table in tables for phrase in table for w in words_of(phrase))


def _hedge_start_only(word: str) -> bool:
    """Whether ``word`` is an amount word only as the first word of a hedge of several words ("lighter"
    of "lighter than", "heavier" of "heavier than"), no number, fraction or one-word hedge: alone, after an
    indefinite article and before the end of its chunk ("a lighter, Bic, 20 g"), it is a noun."""
    from recall import lexicon as lx

    single, sequences, _ = _size_vocabulary()
    numbers = (lx.NUMBER_WORDS, lx.MAGNITUDE_WORDS, lx.FRACTION_WORDS)
    return word in sequences and word not in single and not any(word in t for t in numbers)














def said_in_plural(word: str, text: str) -> bool:
    """Whether ``text`` has ``word`` (singular) in a plural form ("binoculars", "boxes"): an adjective has
    none, so a word said in the plural is a noun whatever its ending."""
    low = text.lower()
    return any(re.search(rf"\b{re.escape(word)}{end}\b", low) for end in ("s", "es")) or (
        word.endswith("y") and re.search(rf"\b{re.escape(word[:-1])}ies\b", low) is not None
    )


#: Words that introduce a noun phrase as the thing spoken of: articles, demonstratives, possessives and
#: counting words ("*a* flyswatter", "*this* toy apple", "*my* daughter's teddy bear", "*one* of the ...").
DETERMINERS = frozenset(
    "a an the this that these those my your our his her their its one some another any each every".split()
)


def introduced(text: str, word: str) -> bool:
    """Whether ``word`` (a head noun of the subject, singular) is introduced by a determiner
    (:data:`DETERMINERS`) earlier in the first clause that has it (clauses end at a comma, semicolon or
    full stop): "a kitchen flipper", "the holder for the toilet brush", "steel, 15 cm long, a nutcracker";
    not "kitchen flipper, nylon", "spring-loaded jaws, 11 cm", "nests with others", "tiny, two screw
    caps": a bare phrase in a list of features may be a part, a verb or an adjective, so it names no
    object the catalog lacks on its own."""
    for clause in re.split(r"[,;]|\.(?!\d)", text.lower()):
        seen = False
        for w in _WORD.findall(clause.replace("'", "").replace("\u2019", "")):
            if w in DETERMINERS:
                seen = True
            elif singular(w) == word or w == word:
                return seen
    return False


def counted_parts(text: str, phrase: Sequence[str]) -> bool:
    """Whether a subject ``phrase`` (singular words) counts several of its head in the plural ("*two*
    screw caps", "*five* fingers", "*nine* holes", "*four* legs"): a description lists the parts the
    object has, it does not name the object (a number word other than "one", the head said in the plural
    in ``text``; "a two-slice toaster" keeps its hyphen, so "two" is no word of its own there)."""
    from recall import lexicon as lx

    if len(phrase) < 2 or phrase[0] == "one" or phrase[0] not in lx.NUMBER_WORDS:
        return False
    return said_in_plural(phrase[-1], text)
