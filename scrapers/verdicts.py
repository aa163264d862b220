"""The rule that judges one extraction against a corpus label (``tests/data/real_pages/README.md``).

**Dimensions right** when every extent the page states is found and every extent extracted is stated:
the record's stated extents (``ProductRecord.dims``, not the catalog axes filled from them) and the
label's ``dims_cm`` pair off one to one, each within :data:`TOLERANCE` (2 %). A page stating none must
give none. A diameter is one stated extent, but a label may list a round object's width and depth as two
equal numbers: an extracted diameter may stand for one or for two equal label values.
**Mass right** when the label's ``mass_g`` and the record's agree within 2 %, or both are None. A page
that is not a product page (``is_product_page`` false) states nothing.

**Invented values** (:func:`invented`): an extracted extent or mass that is not the product's (not within
2 % of the label's value) and is either one the label lists as *not* the product's (``not_product``:
another product's, a size chart's, a package's, a set's) or a number the page states nowhere in any unit
(:func:`page_numbers`). It must be zero on every page.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Any

from scrapers import labelled_pages
from scrapers.records import ProductRecord

__all__ = ["TOLERANCE", "Verdict", "invented", "judge", "page_numbers", "stated_extents", "truth_of"]

TOLERANCE = 0.02
#: Unit factors to cm and to g a page may write a number in (mm, cm, dm, m, in, ft; mg, g, kg, oz, lb).
_CM = (0.1, 1.0, 10.0, 100.0, 2.54, 30.48)
_G = (0.001, 1.0, 1000.0, 28.349523, 453.59237)
_NUMBER = re.compile(r"\d+(?:[.,'’ ]\d{3})*(?:[.,]\d+)?|[.,]\d+")
# The whitespace before a vulgar fraction belongs to its whole number: "(\d+)?\s*" tried a page's every
# blank and scanned the whole run after it, quadratic on pages with long runs of blanks (a 1.2 MB page: 148 s).
_FRACTION = re.compile(r"(?:(\d+)[\s-])?(\d+)/(\d+)|(?:(\d+)\s*)?([½¼¾⅛⅜⅝⅞⅓⅔])")
_VULGAR = {"½": 0.5, "¼": 0.25, "¾": 0.75, "⅛": 0.125, "⅜": 0.375, "⅝": 0.625, "⅞": 0.875, "⅓": 1 / 3, "⅔": 2 / 3}


def within(a: float, b: float, tolerance: float = TOLERANCE) -> bool:
    return labelled_pages.within(a, b, tolerance)


@dataclass
class Verdict:
    dims_right: bool
    mass_right: bool
    problems: list[str] = field(default_factory=list)


def truth_of(label: dict[str, Any]) -> tuple[list[float], float | None]:
    """(stated extents in cm, mass in g) of a label; nothing for a page that is not a product page."""
    if label.get("is_product_page") is False:
        return [], None
    dims = label.get("dims_cm") or []
    return [float(v) for v in dims], (float(label["mass_g"]) if label.get("mass_g") is not None else None)


def stated_extents(record: ProductRecord | None) -> list[tuple[str, float]]:
    """The record's stated extents as (role, cm); [] for no record."""
    if record is None:
        return []
    return [(str(e.get("role", "extent")), float(e["cm"])) for e in record.dims]


def _pair_off(got: list[tuple[str, float]], want: list[float]) -> bool:
    """Whether ``got`` and ``want`` pair off one to one within 2 % (a diameter may take two equal values)."""
    if not got:
        return not want
    (role, value), rest = got[0], got[1:]
    for i, w in enumerate(want):
        if not within(value, w):
            continue
        left = want[:i] + want[i + 1 :]
        if _pair_off(rest, left):
            return True
        if role == "diameter":
            j = next((k for k, x in enumerate(left) if within(value, x)), None)
            if j is not None and _pair_off(rest, left[:j] + left[j + 1 :]):
                return True
    return False


def _readings(got: list[tuple[str, float]]) -> list[list[tuple[str, float]]]:
    """``got``, and ``got`` without a diameter that another extent already states (a round knob's
    ``Width: 13/16"`` and ``Diameter: 13/16"`` are one stated axis; a label lists it once)."""
    out = [got]
    for i, (role, value) in enumerate(got):
        if role == "diameter" and any(within(value, v) for j, (_, v) in enumerate(got) if j != i):
            out.append(got[:i] + got[i + 1 :])
            break
    return out


def dims_right(record: ProductRecord | None, want: list[float]) -> bool:
    for got in _readings(stated_extents(record)):
        if len(got) > len(want) or len(got) < (len(want) + 1) // 2:
            continue
        if _pair_off(sorted(got, key=lambda e: -e[1]), sorted(want, reverse=True)):
            return True
    return False


def judge(record: ProductRecord | None, label: dict[str, Any]) -> Verdict:
    """The verdict of the module doc for ``record`` (None: nothing extracted) against ``label``."""
    want_dims, want_mass = truth_of(label)
    problems = []
    d_ok = dims_right(record, want_dims)
    if not d_ok:
        problems.append(f"dims {[round(v, 3) for _, v in stated_extents(record)]} != {want_dims}")
    got_mass = record.mass_g if record is not None else None
    if want_mass is None:
        m_ok = got_mass is None
    else:
        m_ok = got_mass is not None and within(got_mass, want_mass)
    if not m_ok:
        problems.append(f"mass {got_mass} != {want_mass}")
    return Verdict(d_ok, m_ok, problems)


def _numbers_of(text: str) -> set[float]:
    """Every number the text writes, read with either decimal mark and as a fraction."""
    out: set[float] = set()
    for m in _NUMBER.finditer(text):
        s = m.group(0)
        digits = re.sub(r"[^\d.,]", "", s)
        for reading in (digits.replace(",", ""), digits.replace(".", "").replace(",", "."),
                        digits.replace(",", "."), re.sub(r"[.,]", "", digits)):  # fmt: skip
            try:
                out.add(float(reading))
            except ValueError:
                pass
    for m in _FRACTION.finditer(text):
        if m.group(3):
            whole = float(m.group(1) or 0)
            if float(m.group(3)):
                out.add(whole + float(m.group(2)) / float(m.group(3)))
        elif m.group(5):
            out.add(float(m.group(4) or 0) + _VULGAR[m.group(5)])
    return out


def page_numbers(text: str) -> set[float]:
    """Every number ``text`` (the whole decoded page, scripts included) writes, for :func:`invented`;
    feet and inches also as inches (``5' 3"`` is 63)."""
    numbers = _numbers_of(text)
    for m in re.finditer(r"(\d+)\s*(?:'|′|ft\.?|feet|foot)\s*(\d+(?:\.\d+)?)", text):
        numbers.add(float(m.group(1)) * 12 + float(m.group(2)))
    for m in re.finditer(r"(\d+)\s*(?:lbs?|pounds?)\.?\s*(\d+(?:\.\d+)?)\s*(?:oz|ounces?)", text, re.I):
        numbers.add(float(m.group(1)) * 16 + float(m.group(2)))
    for m in re.finditer(r"(\d+)\s*kg\s*(\d+)\s*g\b", text, re.I):
        numbers.add(float(m.group(1)) * 1000 + float(m.group(2)))
    return numbers


def _stated(value: float, numbers: set[float], factors: tuple[float, ...]) -> bool:
    return any(within(value, n * f) for n in numbers for f in factors if n)


def _not_product_values(label: dict[str, Any], key: str) -> list[float]:
    """The values of ``key`` the label gives other things: ``not_product`` entries, packages, shipping."""
    out = []
    for extra in ("package", "shipping"):
        v = label.get(f"{extra}_{key}")
        for x in v if isinstance(v, list) else [v]:
            if isinstance(x, (int, float)):
                out.append(float(x))
            elif isinstance(x, list):
                out.extend(float(y) for y in x if isinstance(y, (int, float)))
    for entry in label.get("not_product") or []:
        v = entry.get(key)
        if isinstance(v, (int, float)):
            out.append(float(v))
        elif isinstance(v, list):
            out.extend(float(x) for x in v if isinstance(x, (int, float)))
    return out


def invented(record: ProductRecord | None, label: dict[str, Any], numbers: set[float]) -> list[str]:
    """The record's values that are invented (module doc): each as ``"dims 12.5 (size chart)"``."""
    if record is None:
        return []
    want_dims, want_mass = truth_of(label)
    found = []
    other_dims, other_mass = _not_product_values(label, "dims_cm"), _not_product_values(label, "mass_g")
    for _, value in stated_extents(record):
        if any(within(value, w) for w in want_dims):
            continue
        if any(within(value, o) for o in other_dims):
            found.append(f"dims {value:g}: a value the page gives another thing")
        elif not _stated(value, numbers, _CM):
            found.append(f"dims {value:g}: stated nowhere on the page")
    if record.mass_g is not None and not (want_mass is not None and within(record.mass_g, want_mass)):
        if any(within(record.mass_g, o) for o in other_mass):
            found.append(f"mass {record.mass_g:g}: a value the page gives another thing")
        elif not _stated(record.mass_g, numbers, _G):
            found.append(f"mass {record.mass_g:g}: stated nowhere on the page")
    return found
