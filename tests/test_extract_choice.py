"""The one scored choice between candidates (scrapers/choice.py) and the site-wide blocks it weighs.

Pages here are small HTML written here, each mirroring a layout class many stores use: a store header or
aside holding a size guide before the product's own spec rows; an article's own header; a sidebar table."""

from __future__ import annotations

from types import SimpleNamespace

from scrapers import choice
from scrapers.extract import _close, _dims_agree, extract_page
from scrapers.page import Page


def page(body: str) -> str:
    return f"<html lang='de'><head><title>Tisch Eiche</title></head><body>{body}</body></html>"


SIZE_GUIDE_FIRST = page(
    "<aside><h3>Größentabelle</h3><table><tr><th>Abmessungen</th><td>40 x 30 x 2 cm</td></tr></table></aside>"
    "<main><h1>Tisch Eiche</h1><table><tr><th>Abmessungen</th><td>20 x 10 x 5 cm</td></tr>"
    "<tr><th>Gewicht</th><td>1,2 kg</td></tr></table></main>"
)


def test_a_value_in_a_site_wide_block_loses_to_the_main_contents_own():
    # layout class: a store's aside (size guide) or header before the product's spec table
    record = extract_page(SIZE_GUIDE_FIRST, "https://shop.test/p/1", "text/html")
    assert record.dims_cm == (20.0, 10.0, 5.0) and record.mass_g == 1200.0
    by_value = {tuple(c["value"]): c for c in record.candidates if c["feature"] == "dims"}
    assert by_value[(40.0, 30.0, 2.0)]["features"]["main"] == 0.0
    assert by_value[(20.0, 10.0, 5.0)]["features"]["main"] == 1.0
    assert by_value[(40.0, 30.0, 2.0)]["decision"].startswith("not the product's: stated only in a site-wide")


def test_the_size_guide_loses_whatever_the_weights():
    # the same page, scored with a zero weight for "main": the aside's earlier row would win the tie on
    # page order, but a cluster stated only in a site-wide block is never eligible
    from scrapers.adapters.spec_table import spec_table

    p = Page(SIZE_GUIDE_FIRST, "https://shop.test/p/1", "text/html")
    dims = [o for o in spec_table(p) if o.feature == "dims"]
    for o in dims:
        o.source = "spec_table"
    for weights in ({**choice.WEIGHTS, "main": 0.0}, choice.WEIGHTS):
        clusters = choice.choose(dims, _dims_agree, lambda o: 0, 9, weights)
        assert clusters[0].value.value == (20.0, 10.0, 5.0) and clusters[1].site_wide


def test_site_wide_blocks_are_the_store_header_footer_nav_aside_and_their_roles():
    # layout class: header/footer of the page vs an article's own header (HTML's sectioning rule)
    p = Page(page(
        "<header>Kopf 1</header><nav>Nav 2</nav><div role='contentinfo'>Info 3</div>"
        "<article><header>Artikelkopf 4</header><footer>Artikelfuß 5</footer></article>"
        "<section><header role='banner'>Banner 6</header></section><footer>Fuß 7</footer><p>Text 8</p>"
    ), "https://shop.test/", "text/html")  # fmt: skip
    site_wide = {line.text: line.site_wide for line in p.lines}
    assert site_wide == {"Kopf 1": True, "Nav 2": True, "Info 3": True,
                         "Artikelkopf 4": False, "Artikelfuß 5": False, "Banner 6": True, "Fuß 7": True,
                         "Text 8": False}  # fmt: skip
    assert p.site_wide_line(1) and not p.site_wide_line(len(p.lines)) and not p.site_wide_line(-1)


def obs(value, source="a", rank=1, feature="mass", site_wide=False):
    return SimpleNamespace(value=value, source=source, rank=rank, feature=feature, site_wide=site_wide)


def INDEX(o):
    return {"a": 0, "b": 1, "c": 2}[o.source]


def test_features_each_in_zero_to_one():
    members = [obs((30.0, 20.0, 10.0), "a", 0, "dims"), obs((30.0, 20.0), "c", 2, "dims", site_wide=True)]
    assert choice.features(members, INDEX, 3) == {
        "source": 1.0, "direct": 1.0, "support": 0.5, "repeats": 1 / 3, "complete": 1.0, "main": 0.5}
    lone = choice.features([obs(5.0, "c", 2)], INDEX, 3)
    assert lone == {"source": 0.0, "direct": 0.0, "support": 0.0, "repeats": 0.0, "complete": 0.0, "main": 1.0}


def test_the_highest_score_wins_and_equal_scores_keep_priority_order():
    first, second = obs(100.0, "b"), obs(200.0, "b")
    clusters = choice.choose([first, second], _close, INDEX, 3)
    assert clusters[0].members == [first] and clusters[1].members == [second]
    # agreement of another reader outweighs a better source only when its weight says so
    a, b, c = obs(100.0, "a"), obs(200.0, "b"), obs(200.0, "c")
    assert choice.choose([a, b, c], _close, INDEX, 3)[0].members == [a]
    strong = {**choice.WEIGHTS, "support": 8.0}
    assert choice.choose([a, b, c], _close, INDEX, 3, strong)[0].members == [b, c]
    assert choice.choose([], _close, INDEX, 3) == []


def test_a_size_clusters_value_is_its_fullest_member():
    short, full = obs((30.0, 20.0), "a", feature="dims"), obs((30.0, 20.0, 10.0), "b", feature="dims")
    (only,) = choice.choose([short, full], _dims_agree, INDEX, 3)
    assert only.value is full


def test_fit_weights_keeps_the_weights_in_use_unless_others_choose_more_right():
    right, wrong = ({"source": 1.0, "support": 0.0}, True), ({"source": 0.5, "support": 1.0}, False)
    assert choice.fit_weights([[right, wrong]]) == choice.WEIGHTS
    assert choice.fit_weights([[({"source": 1.0}, True)], [right, right]]) == choice.WEIGHTS  # say nothing
    flipped = [[({"source": 1.0, "support": 0.0}, False), ({"source": 0.5, "support": 1.0}, True)]]
    w = choice.fit_weights(flipped)
    assert choice.pick(flipped[0], w) and not choice.pick(flipped[0], choice.WEIGHTS)


FOOTER_ONLY = page(
    "<main><h1>Tisch Eiche</h1><p>Ein schöner Tisch.</p></main>"
    "<footer><p>Versand: Pakete bis 30 kg; Abmessungen: 120 x 60 x 60 cm</p>"
    "<p>Our parcels measure 120 x 60 x 60 cm and weigh up to 30 kg at most.</p></footer>"
)


def test_a_value_stated_only_in_a_site_wide_block_is_never_the_products():
    # layout class: a store footer's shipping limits (spec-like and prose), no product value on the page
    import pytest

    from kb.errors import ExtractionError

    with pytest.raises(ExtractionError, match="only site-wide blocks state one"):
        extract_page(FOOTER_ONLY, "https://shop.test/p/2", "text/html")
    # the same text in the main content is the product's
    main = FOOTER_ONLY.replace("<footer>", "<div>").replace("</footer>", "</div>")
    assert extract_page(main, "https://shop.test/p/2", "text/html").dims_cm == (120.0, 60.0, 60.0)


def test_a_site_wide_cluster_never_wins_even_when_it_scores_higher():
    strong, weak = obs(100.0, "a", 0, site_wide=True), obs(200.0, "c", 2)
    clusters = choice.choose([strong, weak], _close, INDEX, 3)
    assert clusters[0].members == [weak] and clusters[1].site_wide
    (only,) = choice.choose([strong], _close, INDEX, 3)
    assert only.site_wide  # the caller chooses nothing
