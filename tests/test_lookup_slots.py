"""A description stating fewer than three extents, compared with a product page that states all three
(recall.lookup_slots, issue 22): each stated extent may take the slots its word allows ("120 cm wide"
alone: the largest or the middle extent; a length only the largest; a depth or thickness the middle or the
smallest), and the fit takes the placement that fits best. The store is the demo store on 127.0.0.1 with
products written here; the catalog a real DuckDB file of the seed catalog."""

from __future__ import annotations

import pytest

from kb.features import ObjectRecord
from recall.lookup import fits, recall_with_lookup
from recall.lookup_slots import ROLE_SLOTS, extent_role, stated_placements
from recall.parser import parse
from scrapers.demo_store import DemoStore
from scrapers.demo_store.products import P
from scrapers.sources import parse_sources

MONITOR = "a curved gaming monitor, about 120 cm wide, a bit over 12 kg"
WIDE = ObjectRecord.create("wide monitor", a_cm=119.5, b_cm=52.9, c_cm=28.4, mass_g=12600)


def slots(text: str) -> list[dict[str, float]]:
    return [{f: ev.value for f, ev in p.features.items() if f.endswith("_cm")} for p in stated_placements(parse(text))]


@pytest.mark.parametrize(
    ("words", "role"),
    [("about 120 cm wide", "width"), ("5 cm deep", "depth"), ("2 cm thick", "thickness"),
     ("97 cm high", "height"), ("33 cm long", "length"), ("14.7 x 7.2", None)],
)  # fmt: skip
def test_the_role_is_the_extent_word(words, role):
    assert extent_role(words) == role


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("a monitor about 120 cm wide", [{"b_cm": 120.0}, {"a_cm": 120.0}]),  # the parse's first
        ("a rod 33 cm long", [{"a_cm": 33.0}]),  # a length is the largest
        ("a plank 2 cm thick", [{"c_cm": 2.0}, {"b_cm": 2.0}]),  # never the largest
        ("a mug 9 cm tall", [{"a_cm": 9.0}, {"b_cm": 9.0}, {"c_cm": 9.0}]),  # a height: any
        ("a box 30 cm wide and 10 cm tall",  # the order kept: 10 cm never above 30 cm
         [{"a_cm": 30.0, "b_cm": 10.0}, {"a_cm": 30.0, "c_cm": 10.0}, {"b_cm": 30.0, "c_cm": 10.0}]),
        ("a keyboard, 31 x 12 cm", [{"a_cm": 31.0, "b_cm": 12.0}]),  # no extent word: as parsed
        ("a box 30 cm long, 20 cm wide and 10 cm tall", [{"a_cm": 30.0, "b_cm": 20.0, "c_cm": 10.0}]),  # three
    ],
)
def test_stated_extents_take_the_slots_their_words_allow(text, expected):
    assert slots(text) == expected


def test_the_roles_slots_are_the_ordered_slots():
    assert ROLE_SLOTS["length"] == ("a_cm",) and "a_cm" not in ROLE_SLOTS["depth"] + ROLE_SLOTS["thickness"]
    assert ROLE_SLOTS["width"] == ("a_cm", "b_cm") and len(ROLE_SLOTS["height"]) == 3


def test_a_lone_width_fits_a_product_as_its_largest_extent():
    ok, _, score = fits(MONITOR, WIDE)
    assert ok and score < 0.01  # compared as the middle extent only: 120 vs 52.9 cm, 0.28
    # a depth cannot be the largest extent: 120 cm deep is still compared with the middle or smallest
    ok, _, score = fits("a curved gaming monitor, about 120 cm deep, a bit over 12 kg", WIDE)
    assert score > 0.25


@pytest.fixture
def db(seeded_db):
    return seeded_db  # conftest's seed catalog (a fresh copy per test)


def test_the_product_whose_largest_extent_is_the_width_wins_the_names(db):
    wide = P("super-ultrawide-monitor", "jsonld", "en", "Curved Gaming Monitor 49 inch", (119.5, 52.9, 28.4), "cm",
             12.6, "kg", "plastic", "plastic")  # fmt: skip
    tv = P("lcd-tv", "jsonld", "en", "Gaming Monitor TV 37 inch", (92.3, 65.9, 25.3), "cm", 19.4, "kg", "plastic",
           "plastic")  # fmt: skip
    # compared as the middle extent, the TV (0.26) fitted closer than the 120 cm wide monitor (0.28)
    with DemoStore(crawl_delay=None, search_only=(tv, wide)) as store:
        text = f'[[stores]]\nname = "demo"\nbase_url = "{store.base_url}"\nsearch = "{{base_url}}/search?q={{query}}"\n'
        sources = parse_sources("[defaults]\ndelay_s = 0\nread_timeout_s = 5\n" + text, origin="t.toml")
        out = recall_with_lookup(db, MONITOR, sources=sources)
    assert out.looked_up and out.found, out.message
    assert out.result.best.name == "curved gaming monitor 49 inch"
