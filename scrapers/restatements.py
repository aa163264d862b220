"""A value a page states twice: once where nothing says whose it is, once under a label that does.

A description's sentence ("Pendant measures 5/16 x 3/4") names no field, so the free-text reader takes it
for the product's; the same page's spec list says "Pendant measures: 0.3125" x 0.75"", a part's label.
Structured data's bare ``weight: 6.34 kg`` (microdata, JSON-LD) is as often the parcel's: the spec table
says "Versandgewicht: 6,34 kg". The labelled statement says whose the value is: such a candidate that
agrees with a part's, a variant's, a capacity's, a package's or a shipment's labelled value, and with no
labelled product value, is that thing's, not the product's.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from typing import Any

_WORD = re.compile(r"[^\W\d_]{3,}")

#: Adapters that read sentences, not labelled fields.
SENTENCE_SOURCES = frozenset({"free_text"})
#: Adapters whose fields say nothing of whose value it is (a bare ``weight``), beside the sentences'.
UNLABELLED_SOURCES = SENTENCE_SOURCES | {"jsonld", "microdata", "opengraph", "shopify", "woocommerce"}
#: Adapters that read labels ("Versandgewicht", "Pendant measures:").
LABELLED_SOURCES = frozenset({"spec_table", "embedded_json"})
OTHER_THINGS = ("component", "variant", "capacity", "shipping")


def restated_elsewhere(
    valid: Sequence[Any], observations: Sequence[Any], feature: str, agree: Callable[[Any, Any], bool],
) -> list[tuple[Any, Any]]:
    """(sentence candidate, the labelled observation of another thing it agrees with) for every product
    candidate of ``feature`` read from a sentence whose value a labelled field gives to a part, a variant
    or a capacity. A "part" whose head word is a word of the product's name is the product itself ("This vase
    weighs approximately: 1.2 kg" on the vase's page), never evidence (:func:`_names_the_product`)."""
    name_words = {w for o in observations if o.feature == "name" for w in _WORD.findall(str(o.value).lower())}
    labelled = [o for o in observations if o.feature == feature and o.source in LABELLED_SOURCES]
    others = [o for o in labelled if (o.role in OTHER_THINGS or getattr(o, "package", False))
              and not _names_the_product(o.part, name_words)]  # fmt: skip
    products = [o for o in labelled if o.role == "product" and not getattr(o, "package", False)]
    out = []
    for cand in valid:
        if cand.source not in UNLABELLED_SOURCES:
            continue
        if cand.source not in SENTENCE_SOURCES:  # structured data: a package's or a shipment's only
            hits = [o for o in others if o.role == "shipping" or getattr(o, "package", False)]
        else:
            hits = others
        hit = next((o for o in hits if _agrees(cand.value, o.value, feature, agree)), None)
        if hit is not None and not any(_agrees(cand.value, p.value, feature, agree) for p in products):
            out.append((cand, hit))
    return out


def _names_the_product(part: str | None, name_words: set[str]) -> bool:
    """Whether a part's words name the product itself: their last (head) word is a word of its name ("This
    vase" on the vase's page), not only a word before it ("CHANGEdesk's top panel": the panel)."""
    words = _WORD.findall((part or "").lower())
    return bool(words) and words[-1] in name_words


def _agrees(a: Any, b: Any, feature: str, agree: Callable[[Any, Any], bool]) -> bool:
    if feature == "dims":
        a, b = tuple(a), tuple(b)
        return len(a) == len(b) and agree(a, b)
    return agree(a, b)


#: Shop systems whose weight and dimension fields are what the merchant entered for shipping (Shopify's
#: variant grams, WooCommerce's shipping tab): the product's values only when the page labels none.
SHOP_SYSTEM_SOURCES = frozenset({"shopify", "woocommerce"})


def outranked_shop_fields(valid: Sequence[Any], agree: Callable[[Any, Any], bool]) -> list[tuple[Any, Any]]:
    """(shop-system candidate, the labelled product value it disagrees with) for every shop-system weight
    or size that no labelled product value of the feature on the page agrees with, when the page labels
    one (Ridge's ``weight: 150`` in its Shopify data beside "WEIGHT: 2 oz"; a WooCommerce shipping size
    ``7.2 × 7.2 × 9.6 cm`` beside "Overall height (with lid) 86mm")."""
    labelled = [o for o in valid if o.source in LABELLED_SOURCES]
    if not labelled:
        return []
    return [(c, labelled[0]) for c in valid
            if c.source in SHOP_SYSTEM_SOURCES and not any(agree(c.value, o.value) for o in labelled)]  # fmt: skip
