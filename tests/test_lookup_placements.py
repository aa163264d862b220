"""A page that states fewer than three extents (recall.lookup.placements, issue 22): the fit compares them with
the description's sizes they fit best, not as the largest ones ("Width 40 cm, Depth 38 cm" of a stool 75 cm
tall). The store is the demo store on 127.0.0.1 with products written here; the catalog a real DuckDB file."""

from __future__ import annotations

import pytest

from kb.features import ObjectRecord
from recall.fit import THRESHOLDS, Trust
from recall.lookup import fits, placements, recall_with_lookup
from scrapers.demo_store import DemoStore
from scrapers.demo_store.products import P
from scrapers.sources import parse_sources

STOOL = "a bar stool, about 75 cm tall, 40 cm wide and 38 cm deep"


def test_two_extents_take_each_pair_of_slots_largest_first():
    record = ObjectRecord.create("stool", a_cm=40, b_cm=38, mass_g=4000)
    dims = [p.dims_cm for p in placements(record)]
    assert dims == [(40, 38, None), (40, None, 38), (None, 40, 38)]
    assert all(p.mass_g == 4000 and p.name == "stool" for p in placements(record))
    assert [p.dims_cm for p in placements(ObjectRecord.create("disc", a_cm=45))] == [
        (45, None, None), (None, 45, None), (None, None, 45)]  # fmt: skip


@pytest.mark.parametrize("dims", [(75, 40, 38), ()])
def test_three_extents_or_none_are_compared_as_they_are(dims):
    record = ObjectRecord.create("stool", **dict(zip(("a_cm", "b_cm", "c_cm"), dims, strict=False)), mass_g=4000)
    assert placements(record) == [record]


def test_the_extents_a_page_states_are_compared_where_they_fit_best():
    ok, why, score = fits(STOOL, ObjectRecord.create("oak bar stool", a_cm=40, b_cm=38))
    assert ok and score == pytest.approx(0.0) and "0.11" in why  # the missing height is the unknown one
    # a single stated size cannot fit by being compared with nothing: the unknown penalty is above the
    # fit's threshold
    ok, _, _ = fits("a bar stool, about 75 cm tall", ObjectRecord.create("oak bar stool", a_cm=40, b_cm=38))
    assert not ok and THRESHOLDS[Trust.PLAIN] < 1 / 3


@pytest.fixture
def db(seeded_db):
    return seeded_db  # conftest's seed catalog (a fresh copy per test)


def test_the_page_stating_two_sizes_exactly_beats_a_fuller_page_further_off(db):
    oak = P("oak-bar-stool", "jsonld", "en", "Oak Bar Stool", (40.0, 38.0), "cm", None, "kg", "wood", "solid oak",
            dim_labels=("width", "depth"))  # fmt: skip
    pine = P("pine-bar-stool", "jsonld", "en", "Pine Bar Stool", (62.0, 48.0, 44.0), "cm", None, "kg", "wood",
             "pine")  # fmt: skip
    # as the largest two, the oak stool's 40 x 38 cm are 0.28 off, the pine stool's 62 x 48 x 44 cm 0.16
    assert fits(STOOL, ObjectRecord.create("pine bar stool", a_cm=62, b_cm=48, c_cm=44))[2] > 0.11
    with DemoStore(crawl_delay=None, search_only=(pine, oak)) as store:
        text = f'[[stores]]\nname = "demo"\nbase_url = "{store.base_url}"\nsearch = "{{base_url}}/search?q={{query}}"\n'
        sources = parse_sources("[defaults]\ndelay_s = 0\nread_timeout_s = 5\n" + text, origin="t.toml")
        out = recall_with_lookup(db, STOOL, sources=sources)
    assert out.looked_up and out.found, out.message
    assert sorted(out.stores.new_objects) == ["oak bar stool", "pine bar stool"]
    assert out.result.best.name == "oak bar stool"
