"""Distance metrics between a description's features and catalog objects (the paper's section III).

The paper's Joint Probability distance ranks catalog objects by

    d_JP(i, o) = sum_j log(1 + |f_j(i) - f_j(o)|)

over only the features ``j`` the description states (the mask), numeric features in catalog units (cm, g)
and categorical features one-hot, with no normalisation. The baselines (Euclidean, Minkowski p=4, Cosine,
scikit-learn's k-d tree) use the same masked columns. See ``recall/RECALL.md`` for the rules below.

Rules the paper leaves open, decided here (NumPy, the pruned search and the SQL macros all follow them):

* **Qualifiers.** A stated numeric value is a point (``about``/``exact``) or an interval (``at_least`` →
  [v, 1.5v] (:data:`AT_LEAST_SPAN`), ``at_most`` → [0, v], ``range`` → [low, high]). The difference of a catalog value ``x`` is its
  distance to the interval: ``max(low − x, x − high, 0)``; a point is the interval [v, v].
* **Unknown catalog values.** A catalog object whose value of a stated numeric feature is unknown is
  scored as if it were off by :data:`UNKNOWN_NUMERIC_FRACTION` of the stated value (difference
  ``0.5 · v``): worse than a typical human estimate, far better than a wrong object. An unknown category
  is an all-zero one-hot block, so it costs half a mismatch (``log 2`` instead of ``2 log 2``).

The distances of every row of the one-hot catalog matrix, JP and the baselines, are in
:mod:`recall.distances`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, fields
from typing import Any

import numpy as np

from kb.errors import RecallError
from kb.features import CATEGORICAL_FEATURES, CATEGORIES, NUMERIC_FEATURES, validate_features

__all__ = [
    "CATEGORY_CODES",
    "LN2",
    "LOG_STEP",
    "past_the_part",
    "METRICS",
    "MISMATCH_TERM",
    "NumericCondition",
    "FeatureQuery",
    "UNKNOWN_CATEGORY_TERM",
    "UNKNOWN_NUMERIC_FRACTION",
    "feature_terms",
    "jp_term",
    "log_units",
    "relative_errors",
]

#: Metric names accepted by the recall engine and the CLI (``kdtree`` is Euclidean through sklearn's KDTree).
METRICS: tuple[str, ...] = ("jp", "euclidean", "minkowski", "cosine", "kdtree", "jplog")
#: ``jplog`` (not the paper's; the hybrid's default): JP with every numeric feature in log units of
#: :data:`LOG_STEP`, a 10 % step: |Δ| = |ln x − ln v| / ln 1.1, so a 20 % mass error weighs the same for a
#: 20 g and a 2 kg object (in grams it costs log(1 + 0.2 v): more than any category mismatch). See RECALL.md.
LOG_STEP = math.log(1.1)
#: Values below this (cm, g) are this in log units: 0 has no logarithm, and the search wants finite ends.
LOG_FLOOR = 1e-6
MINKOWSKI_P = 4
#: An unknown catalog value of a stated numeric feature counts as off by this fraction of the stated value.
UNKNOWN_NUMERIC_FRACTION = 0.5
#: A bound a person states is near the value: "more than 1.5 cm" is read as [1.5, 1.5 * AT_LEAST_SPAN] cm,
#: "under an ounce" as [28 / AT_MOST_SPAN, 28] g (math.inf: unbounded). See RECALL.md for the measurement.
AT_LEAST_SPAN = 1.5
#: A stated value ("about 300 g", "15 cm long") is a person's rounded estimate: values within this fraction
#: of it cost nothing, and the difference is counted from the edge of that band.
ABOUT_TOLERANCE = 0.0
AT_MOST_SPAN = math.inf
LN2 = math.log(2.0)
#: JP cost of a categorical mismatch: two one-hot columns differ by 1 -> 2 log 2.
MISMATCH_TERM = 2.0 * LN2
#: JP cost of an unknown catalog category (an all-zero block): one column differs by 1 -> log 2.
UNKNOWN_CATEGORY_TERM = LN2
#: Code of each category value within its feature (the order of kb.features' tuples); -1 = unknown.
CATEGORY_CODES: dict[str, dict[str, int]] = {
    f: {v: i for i, v in enumerate(vals)} for f, vals in CATEGORIES.items()
}

_QUALIFIERS = ("about", "exact", "at_least", "at_most", "range")


def as_stored(x: float) -> float:
    """``x`` rounded to float32, the precision of the engine's columns (``recall.snapshot``): a stated
    value equal to a catalog value stays equal (distance 0), and the ranking is unchanged otherwise."""
    return float(np.float32(x)) if math.isfinite(x) else x


def log_units(x: np.ndarray | float) -> np.ndarray | float:
    """Positive values in log units of :data:`LOG_STEP` (ln x / ln 1.1); 0 -> -inf, inf -> inf, NaN stays."""
    if isinstance(x, float) and 0.0 < x < math.inf:  # a query's value: no error state to set (~10x faster)
        return float(np.log(x) / LOG_STEP)
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.log(np.maximum(x, 0.0)) / LOG_STEP
    return float(out) if np.ndim(out) == 0 else out


def jp_term(difference: np.ndarray | float) -> np.ndarray | float:
    """One feature's Joint Probability term ``log(1 + |d|)`` (= −log P(i → o | d))."""
    return np.log1p(np.abs(difference))


@dataclass(frozen=True)
class NumericCondition:
    """A stated numeric feature: the point ``value`` and the interval [low, high] it allows (catalog units)."""

    feature: str
    value: float
    low: float
    high: float
    qualifier: str = "about"
    #: The difference charged to an unknown catalog value; None: UNKNOWN_NUMERIC_FRACTION of the value.
    unknown: float | None = None

    @property
    def unknown_difference(self) -> float:
        """The difference charged to a catalog object whose value is unknown."""
        if self.unknown is not None:
            return self.unknown
        return UNKNOWN_NUMERIC_FRACTION * abs(self.value)

    def log_scaled(self) -> NumericCondition:
        """The same condition in log units (:func:`log_units`); an unknown catalog value still counts as
        off by UNKNOWN_NUMERIC_FRACTION (a factor 1.5)."""
        return _condition(
            self.feature,
            as_stored(float(log_units(self.value))),
            as_stored(float(log_units(max(self.low, LOG_FLOOR)))),  # "at most" keeps a finite lower end
            as_stored(float(log_units(max(self.high, LOG_FLOOR)))),
            self.qualifier,
            _LOG_UNKNOWN,
        )

    def differences(self, x: np.ndarray, unknown: np.ndarray | None = None) -> np.ndarray:
        """Distance of catalog values ``x`` (NaN = unknown) to the interval; unknown gets the fixed penalty.
        ``unknown``: ``np.isnan(x)`` when already at hand (speed only: the same result)."""
        if self.low == self.high:  # a point: |x - v| is max(v - x, x - v, 0) exactly, in fewer passes
            d = np.abs(x - self.low)
        else:
            d = np.maximum(np.maximum(self.low - x, x - self.high), 0.0)
        return np.where(np.isnan(x) if unknown is None else unknown, self.unknown_difference, d)


_LOG_UNKNOWN = float(log_units(1.0 + UNKNOWN_NUMERIC_FRACTION))
_CONDITION_FIELDS = tuple(f.name for f in fields(NumericCondition))


def _condition(*values: Any) -> NumericCondition:
    """A :class:`NumericCondition` of these field values, built without the frozen dataclass's
    ``__setattr__`` per field (~1.1 µs of ~1.5; every ``jplog`` recall builds one per stated number)."""
    cond = object.__new__(NumericCondition)
    cond.__dict__.update(zip(_CONDITION_FIELDS, values, strict=True))
    return cond


@dataclass(frozen=True)
class FeatureQuery:
    """The features a description states: numeric conditions and categorical values (the paper's mask)."""

    numeric: tuple[NumericCondition, ...] = ()
    categorical: tuple[tuple[str, str], ...] = ()

    @property
    def stated(self) -> tuple[str, ...]:
        """Stated features in :data:`kb.features.FEATURES` order."""
        names = {c.feature for c in self.numeric} | {f for f, _ in self.categorical}
        return tuple(f for f in (*NUMERIC_FEATURES, *CATEGORICAL_FEATURES) if f in names)

    def __len__(self) -> int:
        return len(self.numeric) + len(self.categorical)

    def within_classes(self, bins: Mapping[str, tuple[float, float]]) -> FeatureQuery:
        """The query a binned catalog ranks by (``bins``: feature -> (below, above), a stored x standing for
        the class [x / below, x * above], :mod:`recall.catalog_folder`): each stated interval [low, high]
        widened to [low / above, high * below], the stored values whose class meets it. In log units
        (``jplog``) the distance is exactly the distance between the stated interval and the class; in raw
        units (``jp``) the zero region is, the distance outside it is measured to the widened ends."""
        conds = []
        for c in self.numeric:
            below, above = bins.get(c.feature, (1.0, 1.0))
            low = 0.0 if math.isinf(above) else c.low / above
            conds.append(_condition(c.feature, c.value, low, c.high * below, c.qualifier, c.unknown))
        return FeatureQuery(tuple(conds), self.categorical)

    def within_floors(self, floors: Mapping[str, float]) -> FeatureQuery:
        """The query a catalog with open top bins ranks by (``floors``: feature -> the value at or above
        which a stored value is a lower bound, :mod:`recall.catalog_folder`): a stated interval's ends
        above the floor are read as the floor, the top bin ("7 kg" against a top mass bin "1000 g or
        more"), so that the top bin's objects are not ranked below an object whose value is unknown. The
        verdict's errors read the floors themselves (:func:`relative_errors`)."""
        conds = []
        for c in self.numeric:
            f = floors.get(c.feature)
            if f is None or c.high <= f:
                conds.append(c)
                continue
            low = min(c.low, f)
            conds.append(_condition(c.feature, min(c.value, f), low, f, c.qualifier, c.unknown))
        return FeatureQuery(tuple(conds), self.categorical)

    def log_scaled(self) -> FeatureQuery:
        """The query for ``jplog``: numeric conditions in log units, categories unchanged. The same
        values as :meth:`NumericCondition.log_scaled` (tested), in one NumPy pass over every stated
        number rather than nine scalar calls each (every ``jplog`` recall builds one)."""
        if not self.numeric:
            return FeatureQuery((), self.categorical)
        ends = np.array([(c.value, max(c.low, LOG_FLOOR), max(c.high, LOG_FLOOR)) for c in self.numeric])
        with np.errstate(divide="ignore", invalid="ignore"):
            logs = (np.log(np.maximum(ends, 0.0)) / LOG_STEP).astype(np.float32).tolist()
        conds = tuple(
            _condition(c.feature, v, lo, hi, c.qualifier, _LOG_UNKNOWN)
            for c, (v, lo, hi) in zip(self.numeric, logs, strict=True)
        )
        return FeatureQuery(conds, self.categorical)

    def values(self) -> dict[str, Any]:
        """Point values of the stated features."""
        out: dict[str, Any] = {c.feature: c.value for c in self.numeric}
        out.update(dict(self.categorical))
        return out

    @classmethod
    def from_values(
        cls,
        values: Mapping[str, Any],
        qualifiers: Mapping[str, str] | None = None,
        bounds: Mapping[str, tuple[float | None, float | None]] | None = None,
    ) -> FeatureQuery:
        """Build from feature values in catalog units (None/absent = not stated).

        ``qualifiers`` maps a numeric feature to about/exact/at_least/at_most/range and ``bounds`` to its
        (low, high) for ``range`` (or to override the bound of at_least/at_most). Dimensions are taken as
        given (a >= b >= c is the parser's job). Raises :class:`kb.errors.InvalidFeature` for bad values.
        """
        qualifiers = qualifiers or {}
        bounds = bounds or {}
        numeric = []
        for feat in NUMERIC_FEATURES:
            raw = values.get(feat)
            if raw is None:
                continue
            value = validate_features({"mass_g": raw} if feat == "mass_g" else {"a_cm": raw})
            number = value["mass_g"] if feat == "mass_g" else value["a_cm"]
            if number is None:
                continue
            qual = (qualifiers.get(feat) or "about").lower()
            if qual not in _QUALIFIERS:
                raise RecallError(
                    f"unknown qualifier {qual!r} for {feat}; expected one of {', '.join(_QUALIFIERS)}"
                )
            lo_b, hi_b = bounds.get(feat, (None, None))
            if qual == "at_least":
                low = lo_b if lo_b is not None else number
                high = low * AT_LEAST_SPAN
            elif qual == "at_most":
                high = hi_b if hi_b is not None else number
                low = high / AT_MOST_SPAN
            elif qual == "range":
                low = lo_b if lo_b is not None else number
                high = hi_b if hi_b is not None else number
                if low > high:
                    low, high = high, low
            else:
                low, high = number * (1.0 - ABOUT_TOLERANCE), number * (1.0 + ABOUT_TOLERANCE)
            numeric.append(
                NumericCondition(feat, as_stored(number), as_stored(low), as_stored(high), qual)
            )
        categorical = []
        clean = validate_features({f: values.get(f) for f in CATEGORICAL_FEATURES})
        for feat in CATEGORICAL_FEATURES:
            if clean[feat] is not None:
                categorical.append((feat, clean[feat]))
        return cls(tuple(numeric), tuple(categorical))

    @classmethod
    def from_parsed(cls, parsed: Any) -> FeatureQuery:
        """Build from the parser's ``ParsedDescription`` (``.features``: feature -> evidence with ``value``,
        ``qualifier``, ``low``, ``high``)."""
        values: dict[str, Any] = {}
        qualifiers: dict[str, str] = {}
        bounds: dict[str, tuple[float | None, float | None]] = {}
        for feat, ev in (getattr(parsed, "features", None) or {}).items():
            value = getattr(ev, "value", ev)
            if value is None:
                continue
            values[feat] = value
            if feat in NUMERIC_FEATURES:
                qual = getattr(ev, "qualifier", None)
                if qual in _QUALIFIERS:
                    qualifiers[feat] = qual
                low, high = getattr(ev, "low", None), getattr(ev, "high", None)
                bounds[feat] = (_finite_or_none(low), _finite_or_none(high))
        return cls.from_values(values, qualifiers, bounds)


def _finite_or_none(x: Any) -> float | None:
    if x is None:
        return None
    try:
        x = float(x)
    except (TypeError, ValueError):
        return None
    return x if math.isfinite(x) else None


def feature_terms(num: np.ndarray, cat: np.ndarray, query: FeatureQuery) -> dict[str, np.ndarray]:
    """Per stated feature, the JP term of every row: ``num`` is (n, 4) in NUMERIC_FEATURES order (NaN =
    unknown), ``cat`` (n, 5) category codes (-1 = unknown). The per-feature contributions of a match."""
    out: dict[str, np.ndarray] = {}
    for cond in query.numeric:
        out[cond.feature] = np.log1p(cond.differences(num[:, NUMERIC_FEATURES.index(cond.feature)]))
    for feat, value in query.categorical:
        codes = cat[:, CATEGORICAL_FEATURES.index(feat)]
        code = CATEGORY_CODES[feat][value]
        out[feat] = np.where(codes == code, 0.0, np.where(codes < 0, UNKNOWN_CATEGORY_TERM, MISMATCH_TERM))
    return out


def relative_errors(
    num_row: np.ndarray,
    cat_row: np.ndarray,
    query: FeatureQuery,
    floors: Mapping[str, float] | None = None,
    bins: Mapping[str, tuple[float, float]] | None = None,
) -> dict[str, float]:
    """How far one catalog object is from the description, per stated feature, on one scale-free [0, 1]
    scale (the open-set closeness and the confidence use it; the ranking does not):

    * numeric: ``d / max(v, x)``, ``d`` the difference to the stated value or interval (as in JP), ``v``
      the stated value, ``x`` the object's (30 % too long and 30 % too heavy count the same for a coin
      and a sofa); an unknown value counts as the unknown penalty, 1/3 (``0.5 v / 1.5 v``); a value at or
      above the catalog's floor for that feature (``floors``, :mod:`recall.catalog_folder`: "15 cm or more") is a
      lower bound, so only a stated value below it differs; a catalog that records classes, not
      measurements (``bins``, :mod:`recall.catalog_folder`: feature -> (below, above)), has each value
      stand for the class [x / below, x * above] (above infinite: a lower bound, the size of the part
      the data set measured), and only a stated value or interval outside it differs; where the sizes
      are a part's and the object's part reaches the open top size class, its mass class is open above too
      (:func:`past_the_part`);
    * categorical: 0 match, 1 mismatch, 0.5 unknown.
    """
    out: dict[str, float] = {}
    for cond in query.numeric:
        x = float(num_row[NUMERIC_FEATURES.index(cond.feature)])
        if math.isnan(x):
            out[cond.feature] = UNKNOWN_NUMERIC_FRACTION / (1.0 + UNKNOWN_NUMERIC_FRACTION)
            continue
        low, high = _class_of(x, bins.get(cond.feature) if bins else None)
        floor = floors.get(cond.feature) if floors else None
        high = math.inf if floor is not None and x >= floor else high  # the open top bin: never too small
        if cond.feature == "mass_g" and cond.low > high and past_the_part(num_row, floors, bins):
            # what the hand bore of a door on its hinges, a hose on the floor: above it the mass is unknown
            out[cond.feature] = UNKNOWN_NUMERIC_FRACTION / (1.0 + UNKNOWN_NUMERIC_FRACTION)
            continue
        d = max(cond.low - high, low - cond.high, 0.0)
        scale = max(abs(cond.value), abs(x))
        out[cond.feature] = min(d / scale, 1.0) if scale > 0 else 0.0
    for feat, value in query.categorical:
        code = int(cat_row[CATEGORICAL_FEATURES.index(feat)])
        out[feat] = 0.0 if code == CATEGORY_CODES[feat][value] else (0.5 if code < 0 else 1.0)
    return out


def past_the_part(num_row: np.ndarray, floors, bins) -> bool:
    """Whether the catalog measured the part grasped (``bins``: the largest size's class open above, the
    whole at least as large) and this object's part already reaches the open top size class (``floors``:
    "15 cm or more"): the object extends past what was measured, so its recorded mass class (what the
    hand bore: the Yale data set codes its wardrobe door at 750 g, its hose at 240 g, its cord at 65 g)
    is no upper bound of the whole object's mass. False without both declarations. The ranking reads the
    same class (:mod:`recall.openset_classes`)."""
    if not floors or not bins:
        return False
    floor, factors = floors.get("a_cm"), bins.get("a_cm")
    if floor is None or factors is None or not math.isinf(factors[1]):
        return False
    x = float(num_row[NUMERIC_FEATURES.index("a_cm")])
    return not math.isnan(x) and x >= floor


def _class_of(x: float, factors: tuple[float, float] | None) -> tuple[float, float]:
    """The interval a catalog value stands for: [x / below, x * above] (``factors``), [x, x] without."""
    if factors is None:
        return x, x
    below, above = factors
    return x / below, (math.inf if math.isinf(above) else x * above)
