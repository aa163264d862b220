"""What a recall says about its first match, in one line (:func:`verdict`): the same words in the CLI,
``--json``, the HTTP API, the web page and ``grasp plan``."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["GUESS_COMPETITORS", "GUESS_CONFIDENCE", "Verdict", "verdict"]


@dataclass(frozen=True)
class Verdict:
    """What a recall says about its first match, in one line, the same in the CLI, ``--json``, the HTTP
    API and the web page: ``label`` is one of "not in the catalog", "not a close match", "a guess" and
    "close match"; ``text`` the line, with the confidence to two decimals and why."""

    label: str
    text: str

    def to_dict(self) -> dict[str, str]:
        return {"label": self.label, "text": self.text}


#: Competitors (the ranking's effective number of candidates) from which "a guess" says why: many fit.
GUESS_COMPETITORS = 3.0
#: Below this confidence a result is "a guess", at or above it a "close match": the label agrees with
#: the confidence (a 0.89 is no guess, a 0.04 no close match, however many candidates are as good).
GUESS_CONFIDENCE = 0.5


def verdict(result) -> Verdict:
    """The verdict of a :class:`recall.results.RecallResult` (see :class:`Verdict`)."""
    if result.not_in_catalog and result.described is not None:
        noun = result.described
        near = ", ".join(m.name for m in result.matches[:3]) or "nothing (no feature stated)"
        kind = ", ".join(m.name for m in result.same_kind) or "none"
        return Verdict(
            "not in the catalog",
            f"NOT IN THE CATALOG (open set): no {noun.noun!r} (kind: {noun.kind}) in the catalog; physically "
            f"closest: {near}; closest {result.same_kind_as or noun.kind}: {kind}; confidence {result.confidence:.2f}",
        )
    if not result.matches:
        return Verdict("not a close match", f"confidence {result.confidence:.2f}; nothing recalled")
    unused, disagrees = (
        getattr(result, "unused", ()),
        getattr(result, "disagrees", ()),
    )  # duck-typed results too
    if unused:
        refused = ", ".join(repr(w) for w in unused)
        label, said = (
            "not a close match",
            f"NOT a close match: nothing stated is left to compare ({refused} refused)",
        )
    elif disagrees:
        label, said = "not a close match", f"NOT a close match: {_disagreement(result)}"
    elif result.open_set:
        label, said = "not a close match", "NOT a close match (open set): nothing in the catalog is near"
    elif result.confidence < GUESS_CONFIDENCE:
        many = result.competitors >= GUESS_COMPETITORS
        label, said = "a guess", "a guess: many objects fit the description equally" if many else "a guess"
    else:
        label, said = "close match", "close match"
    why = []
    if result.closeness is not None and not unused:  # over what the name implies only: no reason
        why.append(f"mean relative error of the best match {result.closeness:.2f}")
    if result.unknown_noun:
        why.append(f"'{result.unknown_noun}' is no catalog noun")
    if result.competitors >= 1.5:
        why.append(f"about {round(result.competitors)} candidates as good")  # a soft count
    reasons = f" ({'; '.join(why)})" if why else ""
    return Verdict(label, f"confidence {result.confidence:.2f}; {said}{reasons}")


#: How a numeric feature is called in a verdict, and its catalog unit.
_FEATURE_WORDS = {
    "a_cm": ("largest size (a)", "cm"), "b_cm": ("middle size (b)", "cm"), "c_cm": ("smallest size (c)", "cm"),
    "mass_g": ("mass", "g"),
}  # fmt: skip


def _disagreement(result) -> str:
    """Which stated features disagree with the best match, by how much: "the stated mass (56000 g) is
    1000x the tennis ball's (56 g)"."""
    best = result.matches[0]
    stated = result.query.get("values", {})
    parts = []
    for feature in result.disagrees:
        word, unit = _FEATURE_WORDS.get(feature, (feature, ""))
        v, x = float(stated[feature]), float(best.features[feature])
        ratio = max(v, x) / max(min(v, x), 1e-12)
        how = f"{ratio:.0f}x" if v >= x else f"1/{ratio:.0f}"
        parts.append(f"the stated {word} ({v:g} {unit}) is {how} the {best.name}'s ({x:g} {unit})")
    return "; ".join(parts)
