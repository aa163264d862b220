"""Sizes as storefront pages write them: ``A x B [x C]`` groups, lettered axes (``H21.6, W9.1, D1.5cm``),
slashed triples (``30/20/10 cm``), axis words and diameter marks, each value in cm with its role.

Every public function takes any text and never raises: a text without a size gives [].
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from kb.measures.aliases import KINDS
from kb.measures.numbers import NUMBER_PATTERN as _NUMBER
from kb.measures.numbers import parse_number
from kb.measures.text import MAX_TEXT, clean_text
from kb.measures.units import UNIT_PATTERN as _UNIT
from kb.measures.units import length_unit, words_pattern
from scrapers.signs import minus_before

__all__ = ["AXIS_LETTER_ROLES", "AXIS_WORD_AFTER", "Dims", "parse_dims"]

_LENGTHS = [name for name, kind in KINDS.items() if kind == "length"]
_TIMES = r"(?:\s*\bx\b\s*)"  # clean_text writes every times sign as " x "
_SIGN = r"(?:[-\u2212](?=\d))?"  # "27 x -27": a minus sign inside a size (kept: scrapers.signs)

_DIMS_RE = re.compile(
    rf"(?P<n1>{_NUMBER})\s*(?P<u1>{_UNIT})?\s*(?P<l1>\(?\b(?![xX]\b)[a-zA-Z]\b\)?)?"
    rf"{_TIMES}{_SIGN}(?P<n2>{_NUMBER})\s*(?P<u2>{_UNIT})?\s*(?P<l2>\(?\b(?![xX]\b)[a-zA-Z]\b\)?)?"
    rf"(?:{_TIMES}{_SIGN}(?P<n3>{_NUMBER})\s*(?P<u3>{_UNIT})?)?"
)
# An axis letter or word written before a number inside a dimensions value.
_AXIS_PREFIX = re.compile(
    r"(?:(?<=^)|(?<=[\s(:;,*×✕xх]))(?:[LWHDBTPlwhdbtp]|長|长|寬|宽|高|深|厚|幅|奥行き?|高さ|長さ|着丈|丈|全長|全幅|全高|縦|横|厚み|(?i:length|width|height|depth|thickness|"
    r"länge|breite|höhe|tiefe|longueur|largeur|hauteur|profondeur|largo|ancho|alto|altura|profundidad))"
    r"\.?\s*[:=]?\s*(?:約|约)?\s*(?=\d)"
)
_DIAMETER_PREFIX = re.compile(
    rf"(?:(?<=^)|(?<=[\s(:;,]))(?:直径|直徑|[ØøΦφ⌀]|dia\.|diameter|durchmesser|diamètre|diámetro|diametro|"
    rf"диаметр|średnica|průměr|priemer)\s*[:=]?\s*(?P<n>{_NUMBER})",
    re.IGNORECASE,
)


@dataclass(frozen=True)
class Dims:
    """Dimensions found in a text, in the order written, converted to cm (``ranged``: a value was a range)."""

    values_cm: tuple[float, ...]
    text: str
    #: What each value measures (:data:`kb.features.EXTENT_ROLES`), from axis letters or a diameter mark;
    #: "extent" where the text does not say.
    roles: tuple[str, ...] = ()

    def extents(self) -> tuple[tuple[str, float], ...]:
        """``(role, cm)`` per stated value."""
        roles = self.roles or ("extent",) * len(self.values_cm)
        return tuple(zip(roles, self.values_cm, strict=True))


#: Axis letters (en, de: B = Breite, T = Tiefe) and diameter marks, by role.
AXIS_LETTER_ROLES = {
    "L": "length", "W": "width", "B": "width", "H": "height", "D": "depth", "T": "depth",
    "Ø": "diameter", "⌀": "diameter",
}  # fmt: skip


_AXIS_WORD_ROLES = {
    "length": "length", "länge": "length", "longueur": "length", "largo": "length",
    "width": "width", "breite": "width", "largeur": "width", "ancho": "width",
    "height": "height", "höhe": "height", "hauteur": "height", "alto": "height", "altura": "height",
    "depth": "depth", "tiefe": "depth", "profondeur": "depth", "profundidad": "depth", "thickness": "thickness",
}  # fmt: skip
_CJK_AXIS_ROLES = {
    "長": "length", "长": "length", "長さ": "length", "寬": "width", "宽": "width", "幅": "width",
    "高": "height", "高さ": "height", "深": "depth", "奥行": "depth", "奥行き": "depth", "厚": "thickness",
    "丈": "length", "着丈": "length",  # a curtain's or a garment's length
    "全長": "length", "全幅": "width", "全高": "height", "縦": "length", "横": "width", "厚み": "thickness",
}  # fmt: skip


def _letter_role(letter: str | None) -> str:
    """The role an axis letter (or CJK axis word) names; "extent" when none."""
    if not letter:
        return "extent"
    letter = letter.strip("()")
    if letter in _CJK_AXIS_ROLES:
        return _CJK_AXIS_ROLES[letter]
    if letter.lower() in _AXIS_WORD_ROLES:
        return _AXIS_WORD_ROLES[letter.lower()]
    if letter in ("Ø", "⌀"):
        return "diameter"
    return AXIS_LETTER_ROLES.get(letter.upper(), "extent")


def _find_unit(tokens: list[str | None], convert, default: str | None) -> list[float | None]:
    factors = [convert(u) if u else None for u in tokens]
    last = next((f for f in reversed(factors) if f is not None), None)
    if last is None and default:
        last = convert(default)
    return [f if f is not None else last for f in factors]


def parse_dims(text: str, default_unit: str | None = None, decimal_comma: bool | None = None) -> list[Dims]:
    """Every ``A x B [x C]`` group in ``text`` with a length unit (after each term, after the last term,
    or ``default_unit`` from the label), converted to cm. Groups without a length unit are skipped; a
    value stated with a minus sign (``-27 x 27 x 2 cm``) is negative, for the limits to refuse."""
    try:
        return _parse_dims(text, default_unit, decimal_comma)
    except Exception:  # noqa: BLE001 - the contract is "never raises on any text"
        return []


_LETTERED = re.compile(
    rf"(?<![^\W_])(?P<axis>[HWDLBTØ⌀])\.?\s*[:=]?\s*(?P<n>{_NUMBER})"
    rf"(?:\s*(?:(?P<u>(?i:{words_pattern(*_LENGTHS)}))(?![^\W\d_])|(?P<q>''|\")))?"
)
_STANDALONE_X = re.compile(r"\bx\b")
_LETTERED_GAP = re.compile(r"\s*(?:[,;/]|and|x)?\s*")


def _lettered_dims(s: str, default_unit: str | None, decimal_comma: bool | None) -> Dims | None:
    """Argos / John Lewis style ``H21.6, W9.1, D1.5cm`` (axis letters, no times signs), or None."""
    tokens = list(_LETTERED.finditer(s))
    if len(tokens) < 2:
        return None
    run = [tokens[0]]
    for tok in tokens[1:]:
        if _LETTERED_GAP.fullmatch(s[run[-1].end() : tok.start()]) and tok["axis"] not in {
            t["axis"] for t in run
        }:
            run.append(tok)
            if len(run) == 3:
                break
        elif len(run) >= 2:
            break
        else:
            run = [tok]
    if len(run) < 2:
        return None
    units = [t["u"] or t["q"] for t in run]
    factors = _find_unit(units, length_unit, default_unit)
    values = [parse_number(t["n"], decimal_comma) for t in run]
    if any(f is None for f in factors) or any(v is None or v <= 0 for v in values):
        return None
    text = s[run[0].start() : run[-1].end()]
    cm = [round(v * f, 6) for v, f in zip(values, factors, strict=True)]
    return Dims(tuple(cm), text, tuple(_letter_role(t["axis"]) for t in run))


# "(L) 30 cm x (W) 20 cm", "30(W) x 20(D) x 10(H) mm": bracketed axis letters carry no value.
_BRACKETED_AXIS = re.compile(r"\s*\(\s*[LWHDBTlwhdbt]\s*\)")
# "30 x 20 x 10 (cm)": a unit in brackets after the last number.
_BRACKETED_UNIT = re.compile(rf"(?<=\d)\s*\(\s*({_UNIT})\s*\)")
# "Abmessungen (B/H/T): 30/20/10 cm": three numbers separated by slashes (fractions are already decimals).
_SLASHED = re.compile(rf"(?<![\d/])({_NUMBER})\s*/\s*({_NUMBER})\s*/\s*({_NUMBER})(?![\d/])")


# "539.5 x 355.5 (505.5) x 171 mm": another configuration's figure in brackets after one of a size's (a
# monitor's height at its highest stand position); the size is the figures outside the brackets.
_ALTERNATIVE = re.compile(rf"(?<=\d)\s*\(\s*{_NUMBER}\s*\)(?=\s*x\s*\d)")


def _bracketed_unit(m: re.Match) -> str:
    return f" {m.group(1)}" if length_unit(m.group(1)) is not None else m.group(0)


#: An axis word after a number and its unit (``13.3 inches width``, ``3.4 in high``, ``20 cm tall``), read as
#: the axis letter the times-sign pattern knows (``13.3 inches W``).
_AXIS_WORD_LETTER = {
    "width": "W", "wide": "W", "height": "H", "high": "H", "tall": "H", "depth": "D", "deep": "D",
    "length": "L", "long": "L",
}  # fmt: skip
AXIS_WORD_AFTER = re.compile(
    rf"({_NUMBER}\s*(?:{_UNIT}|\"))\s+({'|'.join(_AXIS_WORD_LETTER)})\b", re.IGNORECASE
)


def _parse_dims(text: str, default_unit: str | None, decimal_comma: bool | None) -> list[Dims]:
    s = clean_text(text[:MAX_TEXT])
    if "(" in s:
        s = _BRACKETED_UNIT.sub(_bracketed_unit, _BRACKETED_AXIS.sub("", _ALTERNATIVE.sub("", s)))
    if "/" in s:
        s = _SLASHED.sub(r"\1 x \2 x \3", s)
    if AXIS_WORD_AFTER.search(s):  # "13.3 inches width x 3.4 inches high": the axis letters' places
        s = AXIS_WORD_AFTER.sub(lambda m: f"{m.group(1)} {_AXIS_WORD_LETTER[m.group(2).lower()]}", s)
    if not _STANDALONE_X.search(s):
        lettered = _lettered_dims(s, default_unit, decimal_comma)
        if lettered is not None:
            return [lettered]
    diameters: set[str] = set()
    if _DIAMETER_PREFIX.search(s):  # "直径12cm × 高さ6.5cm", "Ø 12 x 6,5 cm": a round object, d x d x h
        diameters = {m.group("n") for m in _DIAMETER_PREFIX.finditer(s)}
        s = _DIAMETER_PREFIX.sub(lambda m: m.group("n"), s)
    prefixed: list[str] = []
    if _AXIS_PREFIX.search(s):
        prefixed = [p.group(0).strip(" .:=約约") for p in _AXIS_PREFIX.finditer(s)]
        s = clean_text(_AXIS_PREFIX.sub("", s))  # "H 30 cm x W 20 cm", "長37.5*寬26*高13.5cm"
    found: list[Dims] = []
    for m in _DIMS_RE.finditer(s):
        dims = _times_group(m, s, _Marks(diameters, prefixed), default_unit, decimal_comma)
        if dims is not None:
            found.append(dims)
    return found


@dataclass(frozen=True)
class _Marks:
    """What a text says about its values before the groups are read: the numbers written after a
    diameter mark, and the axis words or letters written before numbers, in order."""

    diameters: set[str]
    prefixed: list[str]


def _times_group(
    m: re.Match, s: str, marks: _Marks, default_unit: str | None, decimal_comma: bool | None
) -> Dims | None:
    """One ``A x B [x C]`` match as :class:`Dims`, or None without a length unit or with a value of 0; a
    value written with a minus sign (:func:`scrapers.signs.minus_before`) is kept negative, to be refused."""
    nums = [m.group("n1"), m.group("n2"), m.group("n3")]
    n = 3 if nums[2] is not None else 2
    nums = nums[:n]
    units, letters = _units_and_letters(m, s[m.end() :], n)
    factors = _find_unit(units, length_unit, default_unit)
    if any(f is None for f in factors):
        return None
    values = [parse_number(x, decimal_comma) for x in nums]
    if any(v is None or v <= 0 for v in values):
        return None
    signs = [-1.0 if minus_before(s, m.start(f"n{i + 1}")) else 1.0 for i in range(n)]
    cm = [round(sign * v * f, 6) for sign, v, f in zip(signs, values, factors, strict=True)]
    plain = [i for i, x in enumerate(nums) if x not in marks.diameters]
    if len(marks.prefixed) == len(plain) and all(letter is None for letter in letters):
        for i, letter in zip(plain, marks.prefixed, strict=True):  # "Ø 12 x H 20", "Diameter 30 x Height 15"
            letters[i] = letter
    roles = tuple(
        "diameter" if x in marks.diameters else _letter_role(letter)
        for x, letter in zip(nums, letters, strict=True)
    )
    return Dims(tuple(cm), m.group(0), roles)


def _units_and_letters(m: re.Match, tail: str, n: int) -> tuple[list[str | None], list[str | None]]:
    """The length unit (None where there is none) and the axis letter of each of a match's ``n`` values;
    ``tail`` is the text after the match."""
    units = [m.group("u1"), m.group("u2"), m.group("u3")][:n]
    # A one-letter "unit" like the L/W/H suffix of "23L" is a letter, not a unit; a trailing unit
    # may follow a suffix letter ("30H centímetros"): look past it.
    letters = [m.group("l1"), m.group("l2"), None][:n]
    for i in range(n - 1):  # "23L x 13,8W x ...": a suffix letter read as a unit
        if letters[i] is None and units[i] and len(units[i]) == 1 and length_unit(units[i]) is None:
            letters[i] = units[i]
    if n == 3 and units[2] and len(units[2]) == 1 and length_unit(units[2]) is None:
        letters[2], units[2] = units[2], None
    if n == 3 and letters[2] is None and (after := re.match(r"\s?([a-zA-Z])\b", tail)):
        letters[2] = after.group(1)  # 20"w x 4"d x 16"h
    if units[-1] is None or length_unit(units[-1]) is None:
        t = re.match(rf"\s*(?:\b[a-zA-Z]\b\s*)?({_UNIT})", tail)
        if t and length_unit(t.group(1)) is not None:
            units[-1] = t.group(1)
    return [u if u and length_unit(u) is not None else None for u in units], letters
