"""The models a grasp-family rule may be fitted with, and the object features they read (issue 24, "People").

:data:`CANDIDATES` lists every choice the nested cross-validation of :mod:`sim.human_fit` makes between:
multinomial logistic regression, shallow decision trees and k nearest neighbours, on the ``planner`` or
``ratios`` feature sets (:func:`feature_vector`: what the planner knows of any catalog object, extents, mass,
shape, rigidity and fragility; never a name). :func:`fit_candidate` fits one on weighted rows
(:func:`training_rows`: majorities or, for ``soft``, every recorded family by its share).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from sim.grasps import FAMILIES
from sim.human_families import YaleObject, planner_features

__all__ = [
    "CANDIDATES",
    "FEATURE_SETS",
    "Candidate",
    "family_features",
    "feature_vector",
    "fit_candidate",
    "training_rows",
]

_SHAPES = ("thin", "compact", "prism", "long", "radial")
FEATURE_SETS = ("planner", "ratios")
#: Floor of an extent or a mass before its log (cm, g): the data's smallest bins are 0.15 cm and 1.5 g.
_LOG_FLOOR = 0.05


@dataclass(frozen=True)
class Candidate:
    """One choice the inner loop may make: a model family, its hyper-parameters, features and weights.

    ``param`` is the logistic's ``C``, the tree's depth or k of the neighbours; ``leaf`` the tree's least
    objects a leaf; ``balanced`` weighs each family by the inverse of its share of the training labels;
    ``soft`` trains on every recorded family of an object, weighted by its share, instead of the majority
    only (the label scored stays the majority); ``distance`` weighs neighbours by inverse distance.
    """

    model: str  # "logistic", "tree" or "knn"
    features: str  # a member of FEATURE_SETS
    param: float
    leaf: int = 0
    balanced: bool = False
    soft: bool = False
    distance: bool = False

    @property
    def label(self) -> str:
        if self.model == "logistic":
            core = f"logistic C={self.param:g}"
        elif self.model == "tree":
            core = f"tree depth={int(self.param)} leaf>={self.leaf}"
        else:
            core = f"knn k={int(self.param)}" + (" distance" if self.distance else "")
        flags = [f for f, on in (("balanced", self.balanced), ("soft", self.soft)) if on]
        return " ".join([core, self.features, *flags])


def _candidates() -> tuple[Candidate, ...]:
    """:data:`CANDIDATES`, simplest first (a tie in the inner loop goes to the earlier one)."""
    out: list[Candidate] = []
    for fs in FEATURE_SETS:
        for soft in (False, True):
            for balanced in (False, True):
                out += [Candidate("logistic", fs, c, balanced=balanced, soft=soft) for c in (0.03, 0.1, 0.3, 1.0, 3.0)]
    for fs in FEATURE_SETS:
        for balanced in (False, True):
            out += [
                Candidate("tree", fs, depth, leaf=leaf, balanced=balanced)
                for depth in (2, 3, 4)
                for leaf in (10, 6, 3)
            ]
    for fs in FEATURE_SETS:
        for distance in (False, True):
            out += [Candidate("knn", fs, k, distance=distance) for k in (25, 15, 9, 5)]
    return tuple(out)


#: Everything the inner loop chooses from, fixed before any outer result was seen (module docstring).
CANDIDATES: tuple[Candidate, ...] = _candidates()


def feature_vector(p: Mapping, features: str = "planner") -> list[float]:
    """A rule's inputs from a planner feature dict (``a_cm``, ``b_cm``, ``c_cm``, ``mass_g``, ``shape``,
    ``rigidity``, ``fragility``): 11 numbers for ``planner``, 15 for ``ratios``. Extents are sorted."""
    if features not in FEATURE_SETS:
        raise ValueError(f"features must be one of {FEATURE_SETS}, not {features!r}")
    a, b, c = sorted((float(p["a_cm"]), float(p["b_cm"]), float(p["c_cm"])), reverse=True)
    la, lb, lc, lm = (math.log(max(v, _LOG_FLOOR)) for v in (a, b, c, float(p["mass_g"])))
    flags = [float(p.get("rigidity") == "squeezable"), float(p.get("fragility") == "fragile")]
    out = [la, lb, lc, lm, *flags, *(float(p.get("shape") == s) for s in _SHAPES)]
    if features == "ratios":
        volume = la + lb + lc
        out += [lb - la, lc - la, volume, lm - volume]
    return out


def family_features(o: YaleObject, features: str = "planner") -> list[float]:
    """The fitted rule's inputs for a Yale object: what the planner knows of it (no name, no roundness)."""
    return feature_vector(planner_features(o), features)


def _hard(y: np.ndarray) -> np.ndarray:
    return np.eye(len(FAMILIES))[y]


@dataclass(frozen=True)
class _Constant:
    label: int

    def predict(self, x: np.ndarray) -> np.ndarray:
        return np.full(len(x), self.label)


@dataclass
class _Standardised:
    """A model fitted on features centred and scaled by the training rows only."""

    model: object
    mean: np.ndarray = field(default_factory=lambda: np.zeros(0))
    scale: np.ndarray = field(default_factory=lambda: np.ones(0))

    def fit(self, x: np.ndarray, y: np.ndarray, w: np.ndarray | None = None) -> _Standardised:
        self.mean = x.mean(axis=0)
        sd = x.std(axis=0)
        self.scale = np.where(sd > 1e-12, sd, 1.0)
        z = (x - self.mean) / self.scale
        if w is None:
            self.model.fit(z, y)
        else:
            self.model.fit(z, y, sample_weight=w)
        return self

    def predict(self, x: np.ndarray) -> np.ndarray:
        return self.model.predict((x - self.mean) / self.scale)


def training_rows(target: np.ndarray, balanced: bool = False) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The weighted rows a logistic or a tree is trained on, from ``target`` (objects x FAMILIES: one-hot
    majorities, or each object's shares for ``soft``): one row per (object, family) of positive target,
    weighted by it. ``balanced`` scales each family's rows so that every family present weighs the same in
    total (the sum of all weights is unchanged). Returns (object index, family index, weight)."""
    rows, fams = np.nonzero(target > 0)
    w = target[rows, fams].astype(float)
    if balanced:
        mass = target.sum(axis=0)
        present = mass > 0
        class_w = np.zeros(len(mass))
        class_w[present] = mass.sum() / (present.sum() * mass[present])
        w = w * class_w[fams]
    return rows, fams, w


@dataclass
class _Neighbours:
    """k nearest neighbours by Euclidean distance, a vote per neighbour (``distance``: weighted by 1/d,
    and only the neighbours at distance 0 when there are any); ties go to the earlier family, nearer
    neighbours first on equal distances by training order. (scikit-learn's threaded neighbour search
    costs ~0.1 s a call on a shared 2-core machine; this is the same rule in numpy.)"""

    k: int
    distance: bool = False
    x: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))
    y: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))

    def fit(self, x: np.ndarray, y: np.ndarray) -> _Neighbours:
        self.x, self.y = x, y
        return self

    def predict(self, x: np.ndarray) -> np.ndarray:
        k = min(self.k, len(self.y))
        d = np.sqrt(((x[:, None, :] - self.x[None, :, :]) ** 2).sum(axis=2))
        nearest = np.argsort(d, axis=1, kind="stable")[:, :k]
        out = np.empty(len(x), dtype=int)
        for i, idx in enumerate(nearest):
            di = d[i, idx]
            if not self.distance:
                w = np.ones(k)
            elif (di == 0).any():
                w = (di == 0).astype(float)
            else:
                w = 1.0 / di
            out[i] = int(np.argmax(np.bincount(self.y[idx], weights=w, minlength=len(FAMILIES))))
        return out


def fit_candidate(cand: Candidate, x: np.ndarray, y: np.ndarray, shares: np.ndarray | None = None):
    """``cand`` fitted on rows ``x`` with majorities ``y`` (and, for ``soft``, each row's family shares)."""
    from sklearn.linear_model import LogisticRegression
    from sklearn.tree import DecisionTreeClassifier

    if len(set(y.tolist())) == 1:  # one class only: predict it
        return _Constant(int(y[0]))
    target = shares if (cand.soft and shares is not None) else _hard(y)
    if cand.model == "knn":
        return _Standardised(_Neighbours(int(cand.param), cand.distance)).fit(x, y)
    rows, fams, w = training_rows(target, cand.balanced)
    if cand.model == "logistic":
        lr = LogisticRegression(C=cand.param, solver="newton-cholesky", max_iter=500)
        return _Standardised(lr).fit(x[rows], fams, w)
    if cand.model == "tree":
        tree = DecisionTreeClassifier(
            max_depth=int(cand.param), min_samples_leaf=cand.leaf, random_state=0
        )
        return tree.fit(x[rows], fams, sample_weight=w)
    raise ValueError(f"unknown model {cand.model!r}")
