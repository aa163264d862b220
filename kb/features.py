"""The features vocabulary: the one place that defines an object's features, their units and encoding.

Every other part (catalog storage, parser, recall, scrapers, grasp planner) imports its names from here.

Features (units are catalog units):

========== ======================================================= =========================
feature    meaning                                                 values
========== ======================================================= =========================
a_cm       largest extent, cm                                      0 < a <= 500
b_cm       middle extent, cm (b <= a)                              0 < b <= a
c_cm       smallest extent, cm (c <= b)                            0 < c <= b
mass_g     mass, grams                                             0 < m <= 500 000
shape      shape class (Cutkosky/Feix-style, after the paper [2])  thin compact prism long radial
texture    surface texture                                         smooth medium rough grippy
fragility  how easily it breaks                                    fragile medium sturdy
material   simplified material                                     fabric glass metal paper plastic
                                                                   rubber wood other
rigidity   stiffness (the paper's "stiffness": soft -> squeezable) rigid squeezable floppy
========== ======================================================= =========================

Dimensions given in any order are sorted so that ``a >= b >= c``. Any feature may be unknown (None).
A record's values together must also be a plausible household object (:mod:`kb.plausibility`: at least
10 µm thick and 1 mm long, at least 10 mg, a density over its box a x b x c from 5e-5 to 45 g/cm³).

**Partial sizes.** A page often states fewer than three extents (only a diameter, a height and a diameter,
one length). Each stated extent has a role (:data:`EXTENT_ROLES`); :func:`axes_from_extents` says exactly
which roles fill which axes: every stated extent fills one axis, a diameter fills two when nothing else
names the horizontal extents (a round object: width = depth = diameter), and the axes nobody states stay
unknown (None, after the known ones). Nothing is invented.

Encoding for distance metrics (the paper's section III): the four numeric features as they are, in catalog
units, and each categorical feature one-hot, with no normalisation. :data:`VECTOR_COLUMNS` names the
columns; :func:`encode` returns the vector and a mask of the columns that are known.
"""

from __future__ import annotations

import math
import re
import unicodedata
from collections.abc import Iterable, Mapping
from dataclasses import asdict, dataclass, field, fields, replace
from typing import Any

import numpy as np

from kb.errors import InvalidFeature
from kb.plausibility import check_plausible

__all__ = [
    "CATEGORIES",
    "CATEGORY_ALIASES",
    "CATEGORICAL_FEATURES",
    "CSV_COLUMNS",
    "DIMENSIONS",
    "EXTENT_ROLES",
    "FEATURES",
    "FRAGILITIES",
    "MATERIALS",
    "MAX_DIM_CM",
    "MAX_NAME_CHARS",
    "MAX_MASS_G",
    "NUMERIC_FEATURES",
    "ObjectRecord",
    "RIGIDITIES",
    "SHAPES",
    "TEXTURES",
    "VECTOR_COLUMNS",
    "axes_from_extents",
    "check_name",
    "encode",
    "normalize_category",
    "normalize_name",
    "sort_dims",
    "validate_features",
]

SHAPES: tuple[str, ...] = ("thin", "compact", "prism", "long", "radial")
RIGIDITIES: tuple[str, ...] = ("rigid", "squeezable", "floppy")
MATERIALS: tuple[str, ...] = ("fabric", "glass", "metal", "paper", "plastic", "rubber", "wood", "other")
TEXTURES: tuple[str, ...] = ("smooth", "medium", "rough", "grippy")
FRAGILITIES: tuple[str, ...] = ("fragile", "medium", "sturdy")

DIMENSIONS: tuple[str, ...] = ("a_cm", "b_cm", "c_cm")
NUMERIC_FEATURES: tuple[str, ...] = (*DIMENSIONS, "mass_g")
CATEGORIES: dict[str, tuple[str, ...]] = {
    "shape": SHAPES,
    "texture": TEXTURES,
    "fragility": FRAGILITIES,
    "material": MATERIALS,
    "rigidity": RIGIDITIES,
}
CATEGORICAL_FEATURES: tuple[str, ...] = tuple(CATEGORIES)
FEATURES: tuple[str, ...] = (*NUMERIC_FEATURES, *CATEGORICAL_FEATURES)
#: The canonical catalog CSV header, in this order.
CSV_COLUMNS: tuple[str, ...] = ("name", *FEATURES)

#: What a stated extent measures. "extent" is an extent the page does not name (``30 x 20 x 10 cm``).
EXTENT_ROLES: tuple[str, ...] = ("length", "width", "height", "depth", "diameter", "thickness", "extent")
#: Roles that name a horizontal extent of the object (a diameter beside one of them is not the object's
#: width and depth at once).
_HORIZONTAL_ROLES = frozenset({"length", "width", "depth"})

#: Values past these are refused as absurd for a household object (5 m, 500 kg).
MAX_DIM_CM = 500.0
MAX_MASS_G = 500_000.0

#: Words accepted in catalog files besides the canonical ones (case-insensitive). The parser has its own,
#: much larger, table of everyday words (recall/lexicon.py); this one is for data files.
CATEGORY_ALIASES: dict[str, dict[str, str]] = {
    "rigidity": {"soft": "squeezable", "hard": "rigid", "stiff": "rigid", "flexible": "floppy"},
    "material": {
        "metallic": "metal", "steel": "metal", "aluminum": "metal", "aluminium": "metal",
        "wooden": "wood", "cardboard": "paper", "cloth": "fabric", "textile": "fabric",
        "ceramic": "other", "stone": "other", "silicone": "rubber", "foam": "other",
    },
    "shape": {"flat": "thin", "cylindrical": "prism", "spherical": "radial", "round": "radial"},
    "texture": {"rubbery": "grippy", "fuzzy": "rough"},
    "fragility": {"delicate": "fragile", "breakable": "fragile", "robust": "sturdy"},
}

#: Column names of the encoded feature vector: numeric features, then one-hot columns "feature=value".
VECTOR_COLUMNS: tuple[str, ...] = (
    *NUMERIC_FEATURES,
    *(f"{feat}={val}" for feat, vals in CATEGORIES.items() for val in vals),
)
_VECTOR_INDEX = {col: i for i, col in enumerate(VECTOR_COLUMNS)}


#: Characters no name or alias may hold, whatever path it comes in by (CSV, HTTP, Python, ingestion): control
#: characters, NUL included (the CSV import refuses them, so an export holding one could not be read back).
_UNWRITABLE_NAME = re.compile(r"[\x00-\x08\x0b\x0c\x0e-\x1f\x7f]")
#: The longest object name or alias, whatever path it comes in by (the CSV import, the HTTP API's
#: ``max_length``, ingestion): a longer one is a broken row or page, not an object's name.
MAX_NAME_CHARS = 200


#: Unicode categories no name may hold beyond ASCII: control (Cc: C1 controls), format (Cf: the bidi
#: embeddings, overrides and isolates U+202A-U+202E and U+2066-U+2069, zero-width space, joiners, word
#: joiner, byte-order mark, soft hyphen, ...) and lone surrogates (Cs, which UTF-8 cannot write). A format
#: character is invisible, and a bidi override shows a name reversed in the page, reports and CSV.
_INVISIBLE_CATEGORIES = {"Cc": "control character", "Cf": "invisible format character", "Cs": "lone surrogate"}


def _invisible_character(text: str) -> str | None:
    """How the first character of a category in :data:`_INVISIBLE_CATEGORIES` is named, or None."""
    if text.isascii():  # the ASCII controls are _UNWRITABLE_NAME's; ASCII holds no Cf or Cs
        return None
    for ch in text:
        kind = _INVISIBLE_CATEGORIES.get(unicodedata.category(ch))
        if kind:
            return f"the {kind} U+{ord(ch):04X} {unicodedata.name(ch, '')}".rstrip()
    return None


def check_name(field_name: str, text: str) -> None:
    """Raise :class:`InvalidFeature` when ``text`` cannot be a name or alias: a control character, an
    invisible format character (:data:`_INVISIBLE_CATEGORIES`), or over :data:`MAX_NAME_CHARS` characters.
    The one name rule of every path in (CSV, HTTP, ingestion)."""
    bad = _UNWRITABLE_NAME.search(text)
    if bad:
        raise InvalidFeature(field_name, text[:80], f"contains the control character {bad.group()!r}")
    invisible = _invisible_character(text)
    if invisible:
        raise InvalidFeature(field_name, text[:80], f"contains {invisible}")
    if len(text) > MAX_NAME_CHARS:
        raise InvalidFeature(
            field_name, text[:80] + "...", f"{len(text):,} characters (at most {MAX_NAME_CHARS})"
        )


def normalize_name(name: str) -> str:
    """Catalog key of an object name: lower case, single spaces, trimmed."""
    return " ".join(str(name).lower().split())


def normalize_category(feature: str, value: Any) -> str | None:
    """The canonical word for a categorical ``value`` of ``feature``, or None when blank.

    Raises :class:`InvalidFeature` for an unknown feature or word.
    """
    if feature not in CATEGORIES:
        raise InvalidFeature(feature, value, f"not a categorical feature (one of {', '.join(CATEGORIES)})")
    if value is None:
        return None
    word = " ".join(str(value).lower().split())
    if not word:
        return None
    allowed = CATEGORIES[feature]
    if word in allowed:
        return word
    alias = CATEGORY_ALIASES.get(feature, {}).get(word)
    if alias is not None:
        return alias
    raise InvalidFeature(feature, value, f"unknown {feature}; expected one of {', '.join(allowed)}")


def _number(feature: str, value: Any) -> float | None:
    if value is None:
        return None
    if isinstance(value, str):
        text = value.strip()
        if not text:
            return None
        if "_" in text:  # Python's float() reads "1_000" as 1000; no data file means that
            raise InvalidFeature(feature, value, "not a number (digits, a decimal point, an exponent)")
        try:
            value = float(text)
        except ValueError:
            raise InvalidFeature(feature, value, "not a number") from None
        if math.isnan(value):  # the text "nan" is a mistake in a data file, not "unknown" (that is blank)
            raise InvalidFeature(feature, text, "not a number (write unknown values as a blank cell)")
    if isinstance(value, bool):
        raise InvalidFeature(feature, value, "not a number")
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise InvalidFeature(feature, value, "not a number") from None
    if math.isnan(number):
        return None
    if math.isinf(number):
        raise InvalidFeature(feature, value, "must be finite")
    if number <= 0:
        raise InvalidFeature(feature, value, "must be greater than zero")
    limit, unit = (MAX_MASS_G, "g") if feature == "mass_g" else (MAX_DIM_CM, "cm")
    if number > limit:
        raise InvalidFeature(feature, value, f"absurd for a household object (over {limit:g} {unit})")
    return number


def sort_dims(*dims: float | None) -> tuple[float | None, float | None, float | None]:
    """Known dimensions sorted largest first into (a, b, c); unknown ones (None) fill the tail."""
    known = sorted((d for d in dims if d is not None), reverse=True)
    if len(known) > 3:
        raise InvalidFeature("dimensions", dims, "at most three dimensions")
    padded = known + [None] * (3 - len(known))
    return padded[0], padded[1], padded[2]


def axes_from_extents(extents: Iterable[tuple[str, float]]) -> tuple[float, ...]:
    """The known catalog axes, largest first (1 to 3 values), from the ``(role, cm)`` extents a page states.

    The rule (in this order):

    1. Every stated extent fills one axis, whatever its role (length, width, height, depth, thickness,
       or an unnamed ``extent``).
    2. A ``diameter`` fills **two** axes (the width and depth of a round object) when no length, width or
       depth is stated besides it and there is room (at most three axes): ``diameter 12`` gives
       ``(12, 12)``, ``diameter 7.2, height 21.5`` gives ``(21.5, 7.2, 7.2)``.
    3. With more than three extents, diameters are dropped (a pan's ``Diameter 26 cm`` beside its length,
       width and height measures a part); more than three remaining is refused.
    4. Axes no extent fills stay unknown: the caller stores None for them (see :func:`sort_dims`).

    Raises :class:`InvalidFeature` for an unknown role, a value that is not a positive number, or more than
    three extents left by rule 3.
    """
    pairs = [(str(role), float(value)) for role, value in extents]
    for role, value in pairs:
        if role not in EXTENT_ROLES:
            raise InvalidFeature("extent role", role, f"unknown; expected one of {', '.join(EXTENT_ROLES)}")
        if not value > 0 or math.isinf(value):
            raise InvalidFeature(role, value, "must be a positive finite number")
    if len(pairs) > 3:
        pairs = [(r, v) for r, v in pairs if r != "diameter"]
    if len(pairs) > 3 or not pairs:
        raise InvalidFeature("dimensions", tuple(v for _, v in pairs), "expected 1 to 3 extents")
    roles = {r for r, _ in pairs}
    values = [v for _, v in pairs]
    if "diameter" in roles and not roles & _HORIZONTAL_ROLES and len(values) < 3:
        values.append(next(v for r, v in pairs if r == "diameter"))
    return tuple(sorted(values, reverse=True))


def validate_features(values: Mapping[str, Any]) -> dict[str, Any]:
    """Validated, normalised feature values: numbers as float in catalog units, dims sorted, categories
    canonical, unknown as None. Keys not in :data:`FEATURES` are ignored. Raises :class:`InvalidFeature`."""
    out: dict[str, Any] = {}
    dims = [_number(d, values.get(d)) for d in DIMENSIONS]
    out["a_cm"], out["b_cm"], out["c_cm"] = sort_dims(*dims)
    out["mass_g"] = _number("mass_g", values.get("mass_g"))
    for feat in CATEGORICAL_FEATURES:
        out[feat] = normalize_category(feat, values.get(feat))
    return out


@dataclass(frozen=True)
class ObjectRecord:
    """One catalog object: its name, features (None = unknown), aliases and where its values came from.

    Build one with :meth:`create`, which validates and sorts; the plain constructor trusts its input.
    """

    name: str
    a_cm: float | None = None
    b_cm: float | None = None
    c_cm: float | None = None
    mass_g: float | None = None
    shape: str | None = None
    texture: str | None = None
    fragility: str | None = None
    material: str | None = None
    rigidity: str | None = None
    aliases: tuple[str, ...] = ()
    source: str | None = None
    extra: dict[str, Any] = field(default_factory=dict, compare=False, hash=False)

    @classmethod
    def create(
        cls,
        name: Any,
        *,
        aliases: Iterable[str] = (),
        source: str | None = None,
        extra: Mapping[str, Any] | None = None,
        plausible: bool = True,
        **features: Any,
    ) -> ObjectRecord:
        """Validate ``features`` (see :func:`validate_features`, then, with ``plausible``, the values together:
        :func:`kb.plausibility.check_plausible`) and build a record; a blank name is refused.

        ``plausible=False`` is for a record that is never stored: the object a description asks a grasp for
        (``recall/target.py``), whose sides are the stated ones and the rest a catalog object's."""
        unknown = set(features) - set(FEATURES)
        if unknown:
            raise InvalidFeature(sorted(unknown)[0], features[sorted(unknown)[0]], "not a known feature")
        clean_name = normalize_name(name) if name is not None else ""
        if not clean_name:
            raise InvalidFeature("name", name, "missing name")
        check_name("name", clean_name)
        values = validate_features(features)
        if plausible:
            check_plausible(values)
        clean_aliases = tuple(dict.fromkeys(a for a in (normalize_name(x) for x in aliases) if a and a != clean_name))
        for alias in clean_aliases:
            check_name("aliases", alias)
        return cls(name=clean_name, aliases=clean_aliases, source=source, extra=dict(extra or {}), **values)

    @property
    def dims_cm(self) -> tuple[float | None, float | None, float | None]:
        return (self.a_cm, self.b_cm, self.c_cm)

    def features(self) -> dict[str, Any]:
        """The feature values only, keyed by :data:`FEATURES` (None = unknown)."""
        return {f: getattr(self, f) for f in FEATURES}

    def known_features(self) -> dict[str, Any]:
        return {k: v for k, v in self.features().items() if v is not None}

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        d["aliases"] = list(self.aliases)
        return d

    def with_features(self, **changes: Any) -> ObjectRecord:
        merged = {**self.features(), **changes}
        values = validate_features(merged)
        check_plausible(values)
        return replace(self, **values)


def encode(features: Mapping[str, Any] | ObjectRecord) -> tuple[np.ndarray, np.ndarray]:
    """Encode features as (vector, mask) over :data:`VECTOR_COLUMNS`.

    Numeric features are copied in catalog units; a categorical feature sets its one-hot block (all
    columns of the block are known once the category is known). Unknown features leave their columns
    at NaN with mask False. Values must already be valid (see :func:`validate_features`).
    """
    if isinstance(features, ObjectRecord):
        features = features.features()
    vec = np.full(len(VECTOR_COLUMNS), np.nan)
    mask = np.zeros(len(VECTOR_COLUMNS), dtype=bool)
    for feat in NUMERIC_FEATURES:
        value = features.get(feat)
        if value is not None:
            i = _VECTOR_INDEX[feat]
            vec[i] = float(value)
            mask[i] = True
    for feat, vals in CATEGORIES.items():
        value = features.get(feat)
        if value is None:
            continue
        for val in vals:
            i = _VECTOR_INDEX[f"{feat}={val}"]
            vec[i] = 1.0 if val == value else 0.0
            mask[i] = True
    return vec, mask


def record_fields() -> tuple[str, ...]:
    """Names of the :class:`ObjectRecord` fields (for serialisers)."""
    return tuple(f.name for f in fields(ObjectRecord))
