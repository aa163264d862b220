"""Label/value pairs within one line of text: ``Weight: 2 kg Height: 30 cm``, ``Gewicht 4,7 kg``, ``Length 70
cm, chest width 52 cm``, ``サイズ 文庫判/ページ数 170p/高さ 16cm``.

:func:`split_inline` is what :func:`scrapers.spec_pairs.pairs_from_lines` reads on a line that is no label
of its own (and what the ``embedded_json`` adapter reads in a state string); :func:`has_unit` and
:func:`is_unit` tell a measured number and a unit word from the one unit table.
"""

from __future__ import annotations

import re

from scrapers.labels import LabelInfo, classify_label, classify_other
from scrapers.quantities import clean_text, length_unit, mass_unit

__all__ = ["DIGIT", "has_unit", "is_unit", "split_inline"]

_AXIS_LETTER_END = re.compile(r"(?<=\s)[HWDLBT]\.?\s*$")
_SEPARATOR = re.compile(r"\s*(?::|\s[—–]\s|=)\s*")
DIGIT = re.compile(r"\d")
_MAX_LABEL_WORDS = 6
#: The last field bar before a label (``| lens height:``, ``• Weight:``): the label's words start after it.
_FIELD_BAR = re.compile(r"[|•·](?!.*[|•·])\s*")


def split_inline(text: str) -> list[tuple[str, str, LabelInfo]]:
    """Recognised ``label: value`` pairs within one line (several per line allowed), or a label followed
    directly by a number (``Gewicht 4,7 kg``).

    Before each separator (``:``, a spaced dash, ``=``) the longest run of up to six words that
    :func:`classify_label` recognises is the label; its value runs to where the next label starts (the
    last word before the next separator when that one is not recognised)."""
    text = clean_text(text)
    seps = list(_SEPARATOR.finditer(text))
    labelled: list[tuple[str, LabelInfo, int]] = []  # label, what it names, where its value starts
    starts: list[int] = []  # where each separator's label starts
    prev_end = 0
    for k, sep in enumerate(seps):
        bar = _FIELD_BAR.search(text, prev_end, sep.start()) if k > 0 else None
        if bar:
            prev_end = bar.end()  # "70mm | lens height: 42mm": a new field starts at "|"
        first_field = k == 0 or bar is not None
        words = list(re.finditer(r"\S+", text[prev_end : sep.start()]))
        label_start = bar.start() if bar else prev_end + words[-1].start() if words else sep.start()
        # Before a field's first separator every word is the label's: "Cable length: 75 cm" names a part,
        # not a length ("length" alone is only the label when nothing precedes it).
        shortest = max(1, len(words)) if first_field and len(words) <= _MAX_LABEL_WORDS else 1
        for n in range(min(_MAX_LABEL_WORDS, len(words)), shortest - 1, -1):
            first = words[-n].group(0)
            if k > 0 and (DIGIT.search(first) or is_unit(first.rstrip(";,|"))):
                continue  # "Weight: 2 kg Height: 30 cm", "Height: 30 cm; Width: 20 cm": "kg", "cm;" end the
                # previous value, they start no label
            cand_start = prev_end + words[-n].start()
            info = classify_label(text[cand_start : sep.start()])
            if info is not None:
                labelled.append((text[cand_start : sep.start()], info, sep.end()))
                label_start = cand_start
                break
        else:
            if first_field and words and (other := classify_other(text[prev_end + words[0].start() : sep.start()])):
                labelled.append((text[prev_end + words[0].start() : sep.start()], other, sep.end()))
                label_start = prev_end + words[0].start()
        starts.append(label_start)
        prev_end = sep.end()
    out: list[tuple[str, str, LabelInfo]] = []
    value_starts = {start for _, _, start in labelled}
    recognised = [sep.end() in value_starts for sep in seps]
    for label, info, value_start in labelled:
        end = _value_end(text, value_start, starts, recognised)
        value = text[value_start:end].strip(" ;,|•·")
        if DIGIT.search(value):
            out.append((label, value, info))
    if not seps:
        # "Gewicht 4,7 kg"; "Length 70 cm, chest width 52 cm, in size L": each clause a label and a number
        # "サイズ 文庫判/ページ数 170p/高さ 16cm": fields separated by slashes, each its own clause
        fields = _FIELD_SLASH.search(text) is not None
        clauses = _FIELD_SLASH.split(text) if fields else _CLAUSE.split(text)
        for clause in clauses:
            found = _label_then_number(clause)
            if found is None:
                if clause is clauses[0] and not fields:
                    break
                continue
            out.append(found if len(clauses) == 1 else (found[0], found[1].strip(" ,;"), found[2]))
    return out


# A clause boundary: a comma or semicolon, a space and a word ("4,7 kg", "H21.6, W9.1" have none).
#: A slash between fields (``文庫判/ページ数 170p/高さ 16cm``): followed by two letters, so ``30/20/10 cm`` and
#: ``cm/inch`` are not split.
_FIELD_SLASH = re.compile(r"\s*/\s*(?=[^\W\d_]{2})(?![^\W\d_]{1,6}\b\s*$)")
_CLAUSE = re.compile(r"[;,]\s+(?=[^\W\d_]{2})")


_MEASURED = re.compile(r"\d\s*(?:([^\W\d_]{1,12}\.?)(?![^\W_])|([\"'″]))")


def has_unit(text: str) -> bool:
    """Whether ``text`` holds a number followed by a unit (``2 kg``, ``30"``, ``20"W``)."""
    return any(m.group(2) or is_unit(m.group(1).rstrip(".")) for m in _MEASURED.finditer(text))


def _value_end(text: str, value_start: int, starts: list[int], recognised: list[bool]) -> int:
    """Where a value that starts at ``value_start`` ends: where the next label starts. An unrecognised
    "label" before a separator ends it only once the value holds a measured number (``Weight: Surface
    Pro 9 i5, i7: 879 g`` keeps ``i7: 879 g``; ``Weight: 2 kg Colour: red`` stops before ``Colour``)."""
    for start, known in zip(starts, recognised, strict=True):
        if start >= value_start and (known or has_unit(text[value_start:start])):
            return start
    return len(text)


def _label_then_number(text: str) -> tuple[str, str, LabelInfo] | None:
    m = DIGIT.search(text)
    if not m or m.start() == 0:
        return None
    cut = m.start()
    letter = _AXIS_LETTER_END.search(text[:cut])  # "Size H21.6, W9.1, D1.5cm": H belongs to the value
    if letter:
        cut = letter.start()
    label = text[:cut]
    info = classify_label(label) or classify_other(label)
    return (label.strip(), text[cut:], info) if info is not None else None


def is_unit(text: str) -> bool:
    return len(text) <= 12 and (length_unit(text) is not None or mass_unit(text) is not None)

