"""The lookup on real store pages (issue 22): a loopback store written here (scrapers.corpus_store) sells the
real-page corpus behind a word-overlap search; descriptions written here (tests/data/lookup_real/) are
recalled with a lookup into a real DuckDB catalog. Also the rules the misses were fixed by: when the
lookup starts (recall.lookup.unnamed_subject), what a product found is called (the description's noun as
an alias of the best fit; scrapers.product_names.person_name). The store tests skip when the corpus's
pages are absent (scripts/real_pages.py materialize)."""

from __future__ import annotations

import pytest
import requests
from conftest import SEED_CSV
from hypothesis import given
from hypothesis import strategies as st

from kb.catalog import KnowledgeBase
from kb.features import ObjectRecord
from recall.engine import Recaller
from recall.lookup import described_names, fits, lookup_reason, unnamed_subject
from recall.lookup_eval import load_descriptions, run_trial
from scrapers.corpus import load_corpus
from scrapers.corpus_store import CorpusStore, search, sold
from scrapers.product_names import MAX_NAME_WORDS, person_name
from scrapers.sources import parse_sources

CORPUS = [p for p in load_corpus() if sold(p)]
needs_corpus = pytest.mark.skipif(len(CORPUS) < 40, reason="the real-page corpus is not materialized")

#: Descriptions (of tests/data/lookup_real) each standing for one class of issue 22's misses: a name that
#: is a keyword list ("Garlic press KONCIS stainless steel"), a title in Russian, a noun the recall's
#: match is not ("peanut butter" recalled as a coffee can: found, though its page names no size the
#: extractor reads), two products that fit (the closer one gets the noun), a held-out store.
CLASSES = ("ikea-1f6af87aa3", "shared1-peb-a8a8fc6a31", "newegg-f371fc16a9",
           "shared2-greendb_amazon_de_candy_washer", "yeti-c535fe9e18")  # fmt: skip


@pytest.fixture(scope="module")
def seeded(tmp_path_factory):
    path = tmp_path_factory.mktemp("seed") / "seed.duckdb"
    KnowledgeBase.open(path).import_csv(SEED_CSV)
    return path


@pytest.fixture(scope="module")
def store():
    with CorpusStore(CORPUS) as s:
        yield s


def _trial(seeded, tmp_path, store, row):
    pages = {p.id: p for p in CORPUS}
    with requests.Session() as session:
        sources = parse_sources(store.sources_toml())
        return run_trial(seeded, tmp_path, row, store, sources, session, pages, budget_s=10.0)


def test_the_descriptions_are_data_with_an_expected_page_or_object():
    rows, catalog = load_descriptions(), load_descriptions("catalog_descriptions.jsonl")
    assert len(rows) >= 40 and len(catalog) >= 20
    assert len({r["page"] for r in rows}) == len(rows)
    seed = {line.split(",")[0] for line in SEED_CSV.read_text(encoding="utf-8").splitlines()[1:]}
    assert all(r["object"] in seed for r in catalog)


@needs_corpus
def test_every_description_is_of_a_sold_page_and_the_later_ones_of_development_stores_only():
    from scrapers.corpus_store import sold

    pages = {p.id: p for p in CORPUS}
    rows = load_descriptions()
    assert all(r["page"] in pages and sold(pages[r["page"]]) for r in rows)
    later = [r for r in rows if r.get("written_by")]
    assert len(later) >= 40 and not any(pages[r["page"]].held_out for r in later)


@needs_corpus
def test_the_store_sells_only_pages_that_state_a_size_or_mass_and_finds_them_by_a_title_word(store):
    assert all(p.truth.get("dims_cm") or p.truth.get("mass_g") for p in CORPUS)
    hits = search(store.items, "garlic presses")
    assert hits and hits[0].page.id == "ikea-1f6af87aa3"  # plural s dropped, the most words first
    assert search(store.items, "zzzz qqqq") == [] and search(store.items, "") == []
    body = requests.get(store.base_url + "/search?q=garlic+press", timeout=5).text
    assert f'href="{hits[0].path}"' in body
    page = requests.get(store.url_of("ikea-1f6af87aa3"), timeout=5).content
    assert page == hits[0].page.path.read_bytes()  # the real page, byte for byte


@needs_corpus
def test_the_stores_results_come_ten_a_page_with_a_next_link_while_more_follow(store):
    from scrapers.corpus_store import RESULTS_SHOWN
    from scrapers.store_search import parse_search_page

    hits = search(store.items, "monitor")
    assert len(hits) > RESULTS_SHOWN  # the corpus sells more monitors than one results page shows
    (src,) = parse_sources(store.sources_toml()).stores
    listed, url = [], store.base_url + "/search?q=monitor"
    while url:
        got = requests.get(url, timeout=5)
        page = parse_search_page(got.content, got.url, got.headers["Content-Type"], src)
        assert 0 < len(page.product_urls) <= RESULTS_SHOWN
        listed += page.product_urls
        url = page.next_url
    assert listed == [store.base_url + it.path for it in hits]


@needs_corpus
@pytest.mark.parametrize("page_id", CLASSES)
def test_a_described_product_the_catalog_lacks_ends_as_the_recalls_match(seeded, tmp_path, store, page_id):
    row = next(r for r in load_descriptions() if r["page"] == page_id)
    trial = _trial(seeded, tmp_path, store, row)
    if page_id == "yeti-c535fe9e18":  # held out: measured, never fixed for; the page reads 16.8 x 8.9 cm
        assert trial.looked_up
        return
    assert trial.looked_up and trial.right, trial


@needs_corpus
def test_catalog_objects_are_recalled_without_searching(seeded, tmp_path, store):
    asked = len(store.log)
    for row in load_descriptions("catalog_descriptions.jsonl")[:5]:
        trial = _trial(seeded, tmp_path, store, row)
        assert not trial.looked_up and trial.right, trial
    assert len(store.log) == asked  # the store was never asked


@needs_corpus
def test_the_described_noun_names_the_product_in_later_recalls(seeded, tmp_path, store):
    row = next(r for r in load_descriptions() if r["page"] == "ikea-1f6af87aa3")
    _trial(seeded, tmp_path, store, row)
    again = Recaller.from_db(tmp_path / "trial.duckdb").recall_text("a garlic press")
    assert again.best is not None and again.best.matched_by_name and not again.open_set


def test_the_noun_searched_for_is_given_as_the_alias():
    r = Recaller.from_csv(SEED_CSV)
    res = r.recall_text("a garlic press, 16 cm long")
    assert described_names(res, ("garlic press",)) == ("garlic press",)
    unknown = r.recall_text("an Asustor NAS, 29 x 23 x 22 cm, 6.2 kg")
    assert described_names(unknown, ("asustor nas", "nas")) == ("asustor nas", "nas")
    knob = r.recall_text("a black cabinet knob, about 2 cm across")
    assert described_names(knob, ("black cabinet knob", "knob")) == ("black cabinet knob", "knob")
    plural = r.recall_text("guitar patch cables, 50 g")  # the phrase as written, not made singular
    assert described_names(plural, ("guitar patch cable", "cable")) == ("guitar patch cables", "cable")
    tail = r.recall_text("a Mercedes tail light, 52 x 28 x 19 cm, 920 g")  # "light" heads "light bulb"
    assert described_names(tail, ("mercede tail light", "light"), r.names.heads) == ("mercedes tail light",)


# --- when the lookup starts: the recall's match is not the thing the subject names -----------------------


@pytest.mark.parametrize(
    "text, noun",
    [
        ("crunchy peanut butter, 1 kg, about 14 x 10 x 10 cm", "butter"),  # a coffee can at 0.93
        ("an EVGA GeForce graphics card, 27 cm long and 11 cm wide", "card"),  # a knitted glove
        ("a big YETI tumbler, 20 cm tall and 10 cm wide, about 500 g", "tumbler"),  # a glass vase
    ],
)
def test_a_confident_match_of_another_thing_is_looked_up(text, noun):
    res = Recaller.from_csv(SEED_CSV).recall_text(text)
    if res.open_set:  # the recall itself now doubts the match (the tumbler as a glass vase: 0.35 > 0.15)
        assert lookup_reason(res) is not None
        return
    assert unnamed_subject(res) == noun
    assert f"is no {noun}" in lookup_reason(res)


@pytest.mark.parametrize(
    "text",
    [
        "a tennis ball, 6.5 cm across, 56 g",  # named
        "a steel bottle, 21 cm tall, 650 g",  # named by its head noun
        "A plastic kitchen utensil with a wide flat head, about 35 cm long",  # a generic noun
        "a small round plastic ball-like fruit, about 2 inches across",  # a comparison
        "Paper, 9 by 4 inches, thin.",  # a material
        "A round flat ceramic dish, about 27 cm across, 2.5 cm tall, 550 g",  # dish: English 'plate'
        "It is about 15 cm long and weighs 100 g.",  # no subject
    ],
)
def test_a_match_the_words_allow_starts_no_lookup(text):
    assert unnamed_subject(Recaller.from_csv(SEED_CSV).recall_text(text)) is None


# --- the fit rule: one function, the same for the open-set verdict and a store's product -----------------


def test_a_perfect_fit_fits_whatever_the_stores_name_says():
    text = "a Beko fridge, 184 x 60 x 54 cm, 56 kg"
    for name in ("холодильник beko rcsk 310m20s", "/products/beko-rcsk-310m20s", "beko " * 35 + "fridge"):
        ok, why, score = fits(text, ObjectRecord.create(name.strip(), a_cm=184, b_cm=60, c_cm=54, mass_g=56000))
        assert ok and score == 0.0 and "fits: mean relative error 0.00" in why


def test_fits_is_the_open_set_rule_at_its_boundary():
    from recall.fit import THRESHOLDS, Trust

    limit = THRESHOLDS[Trust.PLAIN]
    edge = 1000 * (1 - limit)
    ok, why, closeness = fits("it weighs exactly 1000 g", ObjectRecord.create("a thing", mass_g=edge))
    assert ok and closeness == pytest.approx(limit) and "at most 0.30" in why
    ok, why, closeness = fits("it weighs exactly 1000 g", ObjectRecord.create("a thing", mass_g=edge - 1))
    assert not ok and closeness > limit and why.startswith("does not fit")


def test_a_feature_the_page_does_not_state_does_not_make_another_product_closer():
    text = "a chrome lamp, 34 cm across and 22 cm high"
    exact = fits(text, ObjectRecord.create("mesmeri halo chrome", a_cm=34, b_cm=22.1))
    near = fits(text, ObjectRecord.create("kinis wall lamp", a_cm=25, b_cm=24, c_cm=18, material="metal"))
    assert exact[0] and near[0]  # both fit (the rule counts the unstated material as half an error) ...
    assert exact[2] < near[2]  # ... but the page stating exactly the sizes is the closer one


def test_the_sizes_both_state_choose_among_fits_before_a_category():
    # a 1.9x size miss hidden by a matching material no longer beats an exact size with a finish word's
    # material (a copper-finish polycarbonate shade)
    text = "a copper lamp shade, 45 cm across"
    shade = fits(text, ObjectRecord.create("copper shade", a_cm=45, b_cm=45, material="plastic"))
    lamp = fits(text, ObjectRecord.create("kinis wall lamp", a_cm=25, b_cm=24, c_cm=18, mass_g=400, material="metal"))
    assert shade[0] and lamp[0] and shade[2] == 0.0 < lamp[2]
    # with no size or mass of both, the features the page states choose
    plain = "a plastic lamp shade, 45 cm across"
    assert fits(plain, ObjectRecord.create("shade", material="plastic"))[2] == 0.0
    assert fits(plain, ObjectRecord.create("shade", material="glass"))[2] == 1.0


# --- a person's name of a product ------------------------------------------------------------------------


@pytest.mark.parametrize(
    "title, name",
    [
        ("ViewSonic VX3276-4K-MHD 32 Inch 4K Monitor, IPS Display with HDR10 and Eye Care", "ViewSonic VX3276-4K-MHD 32 Inch 4K Monitor"),
        ("Galaxy Tab S9 FE (Wi-Fi) | Samsung Levant", "Galaxy Tab S9 FE"),
        ("Microsoft - Surface Laptop - Copilot+ PC - 13.8\" Touchscreen", "Microsoft Surface Laptop"),
        ("Trane PAN02916 Drain Pan, Evaporator, Condensate", "Trane PAN02916 Drain Pan"),
        ("Kyocera Klimaschutz-System Ecosys P3145dn Laserdrucker: Schwarz-Weiß, Duplex", "Kyocera Klimaschutz-System Ecosys P3145dn Laserdrucker"),
        ("iFixit Pro Tech® Toolkit: Computer, Phone, Electronics Repair Kit", "iFixit Pro Tech Toolkit"),
        ("/products/sleep-sound-therapy-system", "sleep sound therapy system"),
        ("https://www.amazon.com/ViewSonic-VX3276-Monitor/dp/B07SRDX1Z1", "ViewSonic VX3276 Monitor"),
        ("Trail 25 Pack", "Trail 25 Pack"),
        # the store's own web address before or after the name names no product (real titles, dev pages)
        ('Play.com (UK) : Samsung Series 5 550 37" LE37B550 / HD 1080p : Electronics - Free Delivery', "Samsung Series 5 550 37 LE37B550"),
        ("NEC MultiSync E274F black Computerbildschirm bei csv-direct.de", "NEC MultiSync E274F black Computerbildschirm"),
        ("Electric Kettle 1.7 L | Argos.co.uk", "Electric Kettle 1.7 L"),
        ("Node.js Design Patterns", "Node.js Design Patterns"),  # a dotted word inside the name: kept
        ("Rakuten.de", "Rakuten.de"),  # nothing but the address: the title itself
        ("x", "x"),
    ],
)  # fmt: skip
def test_a_persons_name_keeps_brand_and_model_and_drops_the_keyword_list(title, name):
    assert person_name(title) == name


@given(st.text(max_size=400))
def test_a_persons_name_is_short_and_never_empty_for_a_title_with_letters(title):
    name = person_name(title)
    assert len(name.split()) <= max(MAX_NAME_WORDS, len(title.split()))
    if sum(ch.isalnum() for ch in title) >= 2:
        assert name.strip()



def test_a_shape_only_the_sizes_imply_is_no_misfit():
    text = "a black cabinet knob, about 2 cm across and 2.9 cm deep"  # "across": round
    derived = ObjectRecord.create("knob bagganäs", a_cm=2.86, b_cm=2.06, c_cm=2.06, shape="compact")
    assert fits(text, derived)[0]  # compact is what 2.86 x 2.06 x 2.06 implies: the sizes decide
    stated = ObjectRecord.create("knob bagganäs", a_cm=2.86, b_cm=2.06, c_cm=2.06, shape="thin")
    assert not fits(text, stated)[0]  # a shape the sizes do not imply was stated by the page: it counts
