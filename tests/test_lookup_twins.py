"""Two stores' pages of one product agree, not compete (scrapers.lookup, issue 22): pages that fit and name
one model number (scrapers.lookup.model_numbers) are written as one object whose values both pages
observe; pages that share only a number with its unit ("128GB") or a series word of fewer than
MIN_MODEL_DIGITS digits stay two products. The store is the demo store on 127.0.0.1 with products written
here; the catalog a real DuckDB file; the fit the real one."""

from __future__ import annotations

import pytest

from kb.catalog import KnowledgeBase
from recall.lookup import recall_with_lookup
from scrapers.demo_store import DemoStore
from scrapers.demo_store.products import P
from scrapers.lookup import MIN_MODEL_DIGITS, model_numbers
from scrapers.sources import parse_sources

TEXT = "an Acme computer monitor, about 61 x 42 x 19 cm, 5.4 kg"


def monitor(handle: str, title: str):
    return P(handle, "jsonld", "en", title, (61.2, 42.0, 19.0), "cm", 5400, "g", "plastic", "plastic")


def _lookup(db, products):
    with DemoStore(crawl_delay=None, search_only=products) as store:
        text = (f'[[stores]]\nname = "demo"\nbase_url = "{store.base_url}"\n'
                f'search = "{{base_url}}/search?q={{query}}"\nsearch_results = 3\n')  # fmt: skip
        sources = parse_sources("[defaults]\ndelay_s = 0\nread_timeout_s = 5\n" + text, origin="t.toml")
        return recall_with_lookup(db, TEXT, sources=sources)


def _objects_of(db, urls) -> set[int]:
    """The catalog objects the pages at ``urls`` were written to."""
    from scrapers.outcomes import page_identity

    wanted = {page_identity(u) for u in urls}
    with KnowledgeBase.open(db).connect() as con:
        rows = con.execute("SELECT url, object_id FROM pages WHERE object_id IS NOT NULL").fetchall()
    return {oid for url, oid in rows if page_identity(url) in wanted}


def test_a_model_number_is_letters_and_enough_digits_and_no_quantity():
    digits = "1" * MIN_MODEL_DIGITS
    assert model_numbers(f"Acme E{digits}F monitor") == {f"e{digits}f"}
    assert model_numbers(f"Acme E{digits[1:]}F monitor") == set()  # a series word: "K2", "S9", "X27"
    assert model_numbers("iiyama G-MASTER GB2470HSU-W5 23.8\" (60.5 cm)") == {"gb2470hsu-w5"}
    assert model_numbers("Apple iPhone 13 (128GB), 20000mAh, 1080p, 165Hz, RTX 4070") == set()  # quantities
    assert model_numbers(None) == set()


@pytest.mark.parametrize(("titles", "one"), [
    (("Acme MultiSync E274F LED Monitor", "Monitor Acme E274F 69 cm"), True),  # one model number: one product
    (("Acme MultiSync E27F LED Monitor", "Monitor Acme E27F 69 cm"), False),  # 2 digits: a series word
    (("Acme Vista 128GB LED Monitor", "Monitor Acme Nova 128GB"), False),  # a quantity with its unit
])  # fmt: skip
def test_two_stores_pages_of_one_model_are_one_object(seeded_db, titles, one):
    out = _lookup(seeded_db, tuple(monitor(f"monitor-{i}", t) for i, t in enumerate(titles)))
    assert out.looked_up and out.found, out.message
    added = [c for c in out.stores.candidates if c.outcome == "added"]
    assert len(added) == 2
    assert len(_objects_of(seeded_db, [c.url for c in added])) == (1 if one else 2)
    assert len(out.stores.new_objects) == (1 if one else 2)
    if one:  # the page read second is named as the first, its own title an alias
        assert added[0].name == added[1].name and out.result.best.name == added[0].name
