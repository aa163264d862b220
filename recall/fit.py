"""The fit: whether an object is close enough to be the described one, and why, as one rule.

Two questions are answered by :func:`judge`, so that they cannot drift apart:

* the recall's open-set verdict (:mod:`recall.engine`): is the best catalog match the described object,
  or is the object not in the catalog?
* the store lookup's judgement of a product page (:func:`recall.lookup.fits`): is this product the
  described object?

Both compare the stated features with the object's by their relative errors
(:func:`recall.metrics.relative_errors`, 0 exact .. 1 far off) and ask for a mean error (the closeness) at
most a threshold set by what the words say about the object (:data:`THRESHOLDS`, a ladder of
:class:`Trust`); a stated size or mass :data:`DISAGREE_FACTOR` or more from the object's, or nothing
stated left to compare, is never a fit. The :class:`Fit` carries a continuous **score** (above 1 = not a
fit) that orders results by how far from a fit they are: the open-set score that AUROC and FPR95 are
computed on (``benchmarks/openset_bench.py``). Figures and the reasons for each number: ``recall/RECALL.md``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from enum import Enum

__all__ = [
    "DISAGREE_FACTOR",
    "FOREIGN_SCORE",
    "NAMED_DISAGREE_FACTOR",
    "THRESHOLDS",
    "Fit",
    "Trust",
    "closeness_of",
    "disagree_factor",
    "disagreeing_features",
    "judge",
]


class Trust(Enum):
    """What the description's words say about the object judged, most trusting first."""

    #: The text names the object by one of its whole names or aliases (or a lexicon synonym of one).
    NAMED = "named"
    #: The words say nothing either way (no name, no foreign noun).
    PLAIN = "plain"
    #: The subject is a noun the catalog's names do not know, or a noun modifier the named object lacks
    #: ("a *salad* plate" named "plate"): a loose match is then more likely another object.
    DOUBTED = "doubted"
    #: The subject names a household noun the catalog has no object for (``recall.openset.describe``):
    #: whatever the features, the object is not in the catalog.
    FOREIGN = "foreign"


#: The largest closeness (mean relative error over the stated features) that is still a fit, per
#: :class:`Trust`; None: never a fit. Chosen on the development sets (RECALL.md, "Open set"): right hybrid
#: matches have closeness p99 0.22, so 0.30 leaves room; a name is evidence too (0.45 = 1.5 x 0.30); an
#: unknown noun with a loose match (0.15) is more often another object than a synonym.
THRESHOLDS: dict[Trust, float | None] = {
    Trust.NAMED: 0.45,
    Trust.PLAIN: 0.30,
    Trust.DOUBTED: 0.15,
    Trust.FOREIGN: None,
}

#: A stated size or mass at least this factor from the object's disagrees with it, whatever the rest
#: ("a tennis ball 6.4 cm 56 kg": the mass 1000x off, mean error 0.20). Over the 943 results of the
#: development and blind sets no right first match has a feature off by more than 3x.
DISAGREE_FACTOR = 4.0
#: ... and this factor when the text names the object by a whole name (:attr:`Trust.NAMED`): a name is
#: evidence, so it widens the misfit a value may have by the same ratio as the closeness thresholds
#: (0.45 / 0.30 = 1.5; 6x). On real catalogs a person's kitchen-scale guess of a named object ("a box of
#: Kleenex tissues, 250 grams" for a 40 g class, "a roll of duct tape, 300 g" for 47.5 g) is 4.2x off
#: the class, while no description of an object the catalog lacks that a value 4-12x off flagged was
#: named (RECALL.md, issue 23); "a tennis ball 6.4 cm 56 kg" (1000x) still never fits.
NAMED_DISAGREE_FACTOR = DISAGREE_FACTOR * 1.5
#: The score of an object the words say is not in the catalog (plus its closeness, capped at 1, so such
#: results still order among themselves): above every score a feature misfit alone gives but 1e6.
FOREIGN_SCORE = 10.0
_NUMERIC = ("a_cm", "b_cm", "c_cm", "mass_g")
_WORDS = {"a_cm": "largest size", "b_cm": "middle size", "c_cm": "smallest size", "mass_g": "mass"}


@dataclass(frozen=True)
class Fit:
    """The judgement: ``close`` (a fit), ``score`` (not a fit exactly when above 1; larger is farther) and
    the ``reason`` in words, with the numbers it was decided on."""

    close: bool
    score: float
    reason: str

    def to_dict(self) -> dict[str, object]:
        return {"close": self.close, "score": self.score, "reason": self.reason}


def disagreeing_features(errors: Mapping[str, float], factor: float = DISAGREE_FACTOR) -> tuple[str, ...]:
    """The stated numeric features (``errors``: :func:`recall.metrics.relative_errors`) at least
    ``factor`` from the object's value (relative error ``d / max(v, x)`` of at least
    1 - 1 / factor; an unknown catalog value never disagrees), in feature order."""
    limit = 1.0 - 1.0 / factor - 1e-9
    return tuple(f for f in _NUMERIC if errors.get(f, 0.0) >= limit)


def disagree_factor(trust: Trust) -> float:
    """How far off a stated value may be before it disagrees, given what the words say (:data:`DISAGREE_FACTOR`,
    :data:`NAMED_DISAGREE_FACTOR` for a named object)."""
    return NAMED_DISAGREE_FACTOR if trust is Trust.NAMED else DISAGREE_FACTOR


def closeness_of(errors: Mapping[str, float], silent: Sequence[str] = ()) -> float | None:
    """The closeness: the mean relative error over the stated features (``errors``) except those the
    object's record is ``silent`` on, a category it does not hold (a catalog that records no material
    says nothing about a stated "plastic": counting it half a mismatch made every stated category pull a
    right match toward "not a fit"); None when nothing is left to compare."""
    kept = [e for f, e in errors.items() if f not in silent]
    return sum(kept) / len(kept) if kept else None


def _ratio(error: float) -> float:
    """How many times off a relative error ``d / max(v, x)`` is (0.75 -> 4x)."""
    return 1.0 / max(1.0 - error, 1e-6)


def judge(
    closeness: float | None,
    errors: Mapping[str, float],
    trust: Trust,
    unused: Sequence[str] = (),
    noun: str | None = None,
) -> Fit:
    """Whether the object is a fit (module docstring): ``closeness`` the mean of ``errors`` (None when
    nothing was compared: the text states no feature, only names); ``trust`` what the words say;
    ``unused``: the stated values refused so that nothing was left to compare; ``noun``: the foreign noun
    when ``trust`` is :attr:`Trust.FOREIGN` (for the reason)."""
    threshold = THRESHOLDS[trust]
    mean = 0.0 if closeness is None else closeness
    if threshold is None:
        score = FOREIGN_SCORE + min(mean, 1.0)
        why = f"no {noun!r} in the catalog" if noun else "the words name no object of the catalog"
        return Fit(False, score, why)
    score = mean / threshold
    said = f"mean relative error {mean:.2f} (at most {threshold:.2f}, {trust.value})"
    factor = disagree_factor(trust)
    far = disagreeing_features(errors, factor)
    if far:
        worst = max(_ratio(errors[f]) for f in far)
        score = max(score, 1.0 + math.log(worst / factor) + 1e-6)
        parts = ", ".join(f"the stated {_WORDS[f]} {_ratio(errors[f]):.0f}x off" for f in far)
        return Fit(False, score, f"{parts} (at most {factor:g}x)")
    if unused:
        refused = ", ".join(repr(w) for w in unused)
        return Fit(False, max(score, 2.0), f"nothing stated is left to compare ({refused} refused)")
    if closeness is None:
        return Fit(True, 0.0, "nothing stated to compare")
    close = closeness <= threshold
    return Fit(close, score, ("fits: " if close else "does not fit: ") + said)
