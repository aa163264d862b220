"""The verdict on a recall's best match: is the described thing in the catalog, how far is the match's name
trusted, how close is an object to the stated features.

:func:`verdict` decides, for the best-ranked row, whether the described noun is in the catalog at all and
the :class:`~recall.fit.Trust` its name earns (named, plain, doubted by an unknown noun or a foreign
modifier, foreign); :func:`row_closeness` and :func:`row_fits` are the open-set rule's errors and judgement
of any row (:mod:`recall.openset_named` ranks a fitting named row first by them). Split from
:mod:`recall.engine` (no behaviour change); ``rec`` is the :class:`recall.engine.Recaller`. Rules:
``recall/RECALL.md``, "Open set and confidence".
"""

from __future__ import annotations

import dataclasses
from typing import Any

from kb.features import CATEGORICAL_FEATURES
from kb.kinds import words_of
from recall.catalog_kinds import plain_name
from recall.fit import Trust, closeness_of
from recall.metrics import FeatureQuery, relative_errors
from recall.name_index import NameEvidence
from recall.openset import (
    DescribedNoun,
    foreign_modifier,
    material_agrees,
    names_inside,
    synonym_rows,
    trust_of,
)
from recall.openset_named import fits_by
from recall.vague import SoftEvidence

__all__ = ["Verdict", "foreign_modifier_of", "row_closeness", "row_fits", "silent_categories", "verdict"]


@dataclasses.dataclass(frozen=True)
class Verdict:
    """What :func:`verdict` decides of the best match."""

    not_in_catalog: bool
    unknown: str | None
    modifier: str | None
    trust: Trust


def verdict(
    rec: Any,
    best: int,
    matches: list,
    names: NameEvidence,
    noun: DescribedNoun | None,
    subject: tuple[str, ...],
    not_in_catalog: bool,
) -> Verdict:
    """Whether the described thing is in the catalog at all, and how far the best match's name is
    trusted: its unknown noun or foreign modifier, if any (``not_in_catalog``: the noun's own verdict)."""
    # a whole catalog name in the text beats the subject's noun, unless it is only a modifier of it ("an
    # *egg* cup", "a *pencil* sharpener": the egg and the pencil are not what is described)
    named_whole = matches[0].matched_by_name and not names_inside(noun, names.phrases)
    not_in_catalog = not_in_catalog and not named_whole
    if noun is not None and noun.sort_of is not None and not named_whole:
        # a sort of a catalog object ("a spring clamp"): in the catalog only as an object of that head
        not_in_catalog = words_of(rec.snapshot.names[best])[-1:] != [noun.sort_of]
    # a lexicon synonym of a catalog object ("cellphone", "pen drive": smartphone, usb stick) is no
    # unknown noun, and names it with all its words
    unknown = None if noun is not None and noun.in_catalog else names.unknown_noun
    synonym = best in synonym_rows(noun, rec.names.phrases)
    modifier = foreign_modifier_of(rec, subject, best, names)
    modifier = None if synonym and modifier in noun.noun.split() else modifier
    # a noun before the head of an object named by its head alone says which sort ("a *table* knife" of
    # the catalog's "knife"): neither doubt nor a name's evidence
    narrows = modifier is not None and plain_name(words_of(rec.snapshot.names[best]))
    modifier = None if narrows else modifier
    trusted = (
        (matches[0].matched_by_name or synonym)
        and modifier is None
        and not narrows
        and material_agrees(subject, matches[0].features.get("material"))
    )
    trust = Trust.FOREIGN if not_in_catalog else trust_of(trusted, unknown or modifier)
    return Verdict(not_in_catalog, unknown, modifier, trust)


def row_closeness(rec: Any, row: int, query: FeatureQuery, soft: SoftEvidence | None) -> tuple[dict, float | None]:
    """The relative errors of ``row`` against the stated features and its closeness (their mean)."""
    snap = rec.snapshot
    errors = relative_errors(snap.num_rows(row), snap.cat_rows(row), query, rec.floors, rec.bins)
    errors.update(soft.errors_of(row) if soft is not None else {})
    return errors, closeness_of(errors, silent_categories(snap, row))


def row_fits(rec: Any, row: int, query: FeatureQuery, soft: SoftEvidence | None, subject, trust: Trust) -> bool:
    """Whether ``row`` is a close match by the open-set rule (:func:`recall.openset_named.fits_by`); a
    whole name whose material the subject's words contradict is trusted as a head noun only."""
    if trust is Trust.NAMED and not material_agrees(subject, rec.snapshot.record(row).material):
        trust = Trust.PLAIN
    errors, closeness = row_closeness(rec, row, query, soft)
    return fits_by(closeness, errors, trust)


def silent_categories(snapshot, row: int) -> tuple[str, ...]:
    """The categorical features the catalog holds no value for at ``row`` (code < 0)."""
    codes = snapshot.cat_rows(row)
    return tuple(f for f, code in zip(CATEGORICAL_FEATURES, codes, strict=True) if code < 0)


def foreign_modifier_of(rec: Any, subject: tuple[str, ...], row: int, names: NameEvidence) -> str | None:
    """The noun before the subject's head that none of the named best match's names has
    (:func:`recall.openset.foreign_modifier`); None when the text does not name that row."""
    if not subject or (row not in names.exact and row not in names.head):
        return None
    snap = rec.snapshot
    words = frozenset(w for name in (snap.names[row], *snap.aliases[row]) for w in words_of(name))
    # a phrase of the text that names the row (a synonym: "cross head screwdriver") holds its modifier
    said = [p.split() for p in names.phrases if row in (rec.names.phrases.get(tuple(p.split())) or ())]
    return foreign_modifier(subject, words | frozenset(w for p in said for w in p))
