"""Values the spec reader must not give the product (issue 21's invented values), and net contents and
unitless weights it must read (issue 22's misses), on small pages written here. Each rule is pinned at its
boundary: the classes of development pages (a monitor's stand positions, a review site's photo caption, a
sandal's branded sole, a shop's own measurement of the boxed item, a grocer's size row, metric spec sheets
without units, a review form's height brackets, a cup's fluid ounces, a desk converter's tagline)."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from kb.errors import ExtractionError
from scrapers.extract import extract_page
from scrapers.restatements import _names_the_product
from scrapers.value_forms import bound_value, branded_part, fluid_ounces, note_words, sentence_value


def _read(rows: str, title: str = "Monitor 27 inch", lang: str = "de"):
    html = (f"<html lang='{lang}'><head><title>{title}</title></head><body><h1>{title}</h1><p>Gut.</p>"
            f"<table>{rows}</table></body></html>")  # fmt: skip
    try:
        return extract_page(html, "https://shop.example/p/1", "text/html")
    except ExtractionError:
        return None


def _row(label: str, value: str) -> str:
    return f"<tr><th>{label}</th><td>{value}</td></tr>"


def _extents(record) -> list[float]:
    return sorted((e["cm"] for e in record.dims), reverse=True) if record else []


# -- an adjustable product's highest setting, written in the value, beside its lowest ------------------------

HIGH = _row("Abmessungen (B x T x H)", "60 cm x 19 cm x 49 cm - mit Standfuß (höchste Position)")
LOW = _row("Abmessungen mit Standfuß", "60 cm x 19 cm x 39 cm (niedrigste Position)")


def test_the_highest_setting_is_not_the_product_size_when_the_lowest_is_stated():
    assert _extents(_read(HIGH + LOW)) == [60.0, 39.0, 19.0]
    assert _extents(_read(LOW + HIGH)) == [60.0, 39.0, 19.0]


def test_a_lone_highest_setting_is_still_the_products():
    assert _extents(_read(HIGH)) == [60.0, 49.0, 19.0]


@pytest.mark.parametrize("high", ["(highest position)", "(maximum setting)", "(position la plus haute)"])
def test_the_highest_setting_in_other_words(high):
    rows = _row("Dimensions", f"60 x 19 x 49 cm {high}") + _row("Dimensions", "60 x 19 x 39 cm (lowest position)")
    assert _extents(_read(rows, lang="en")) == [60.0, 39.0, 19.0]


# -- a sentence under a label (a photo caption) is not the label's value -------------------------------------

@pytest.mark.parametrize(
    ("value", "sentence"),
    [("The keyboard is placed on a 900 x 400 mm desk pad.", True),
     ("It sits on a 90 x 40 cm pad", True),
     ("placed on a 90 x 40 cm pad", False),  # three words: not yet a sentence
     ("Set Size(WXDXH) with Stand: 923 x 253 x 659.4", False),  # a sub-label's colon
     ("Breite x Höhe x Tiefe 30 x 20 x 10 cm", False),  # the words are a measurement label
     ("approx. 30 x 20 cm", False), ("30 x 20 cm", False), ("no figure at all here", False)],
)  # fmt: skip
def test_sentence_value_at_its_word_count(value, sentence):
    assert sentence_value(value) is sentence


def test_a_caption_under_dimensions_gives_no_size():
    rows = _row("Dimensions", "The keyboard is placed on a 900 x 400 mm desk pad next to a mouse.")
    rows += _row("Height", "3.2 cm") + _row("Depth", "12 cm")
    assert _extents(_read(rows, "Keyboard K2", "en")) == [12.0, 3.2]
    assert _extents(_read(_row("Dimensions", "placed on 900 x 400 mm"), "Keyboard K2", "en")) == [90.0, 40.0]


@given(st.text(max_size=60))
def test_sentence_value_never_raises_and_needs_a_figure(text):
    assert sentence_value(text) in (True, False)
    if not any(c.isdigit() for c in text):
        assert sentence_value(text) is False


# -- a branded part named in the value ------------------------------------------------------------------------

@pytest.mark.parametrize(
    ("value", "part"),
    [("Vibram® 5mm", "Vibram"), ("Gore-Tex™ membrane 0.3 mm", "Gore-Tex"), ("5 mm Vibram®", None),
     ("5mm", None), ("approx. 5 mm", None)],
)  # fmt: skip
def test_branded_part_before_the_figure(value, part):
    assert branded_part(value) == part


def test_a_thickness_naming_a_branded_sole_is_not_the_products():
    assert _read(_row("Thickness", "Vibram® 5mm"), "Sandal Zero", "en") is None
    assert _extents(_read(_row("Thickness", "5mm Vibram®"), "Sandal Zero", "en")) == [0.5]


@given(st.text(max_size=60))
def test_branded_part_is_a_word_of_the_value(text):
    part = branded_part(text)
    assert part is None or part in text


# -- a size measured with the packed weight is the package's ----------------------------------------------------

PACKED = _row("Gewicht", "5.197kg [Eigenmessung inkl. Verpackung & Beilagen]")


def test_a_size_sharing_the_packed_weights_note_is_the_packages():
    record = _read(_row("Außenmaße (B x T x H)", "160 mm x 680 mm x 440 mm [Eigenmessung]") + PACKED)
    assert record.dims == [] and record.package_dims_cm == [(68.0, 44.0, 16.0)]


@pytest.mark.parametrize("note", ["", " [Herstellerangabe]"])
def test_a_size_with_no_or_another_note_stays_the_products(note):
    record = _read(_row("Außenmaße (B x T x H)", f"160 mm x 680 mm x 440 mm{note}") + PACKED)
    assert _extents(record) == [68.0, 44.0, 16.0]


def test_note_words():
    assert note_words("160 mm [Eigenmessung]") == {"eigenmessung"}
    assert note_words("5 kg") == frozenset()


# -- a size row's net content beside the weight in the name ---------------------------------------------------

def test_a_size_rows_mass_beats_the_names_when_the_name_states_one():
    record = _read(_row("Size", "275g"), "Avocado Ripe & Ready XL Loose 300g", "en")
    assert record.mass_g == 275.0


def test_a_size_rows_mass_alone_is_no_weight():
    assert _read(_row("Größe", "1KG"), "Kaffee Bio Bohnen") is None


def test_a_labelled_weight_still_beats_a_size_row():
    record = _read(_row("Size", "275g") + _row("Weight", "280 g"), "Avocado XL 300g", "en")
    assert record.mass_g == 280.0


# -- a unitless weight on a spec sheet whose unitless lengths are millimetres --------------------------------

SHEET = _row("Breite", "540,00") + _row("Höhe", "379,00") + _row("Länge", "233,00")


def test_a_unitless_weight_beside_millimetre_lengths_is_kilograms():
    record = _read(SHEET + _row("Gewicht", "5,00"))
    assert record.mass_g == 5000.0 and _extents(record) == [54.0, 37.9, 23.3]


def test_a_unitless_weight_beside_lengths_of_unknown_unit_stays_unread():
    # 54 / 37.9 / 23.3 are within the cm limit: nothing says mm, so nothing says kg
    record = _read(_row("Breite", "54") + _row("Höhe", "37,9") + _row("Gewicht", "5,00"))
    assert record is None or record.mass_g is None


# -- a bound written with a comparison sign; ounces beside a volume --------------------------------------------

@pytest.mark.parametrize(
    ("value", "bound"),
    [("<5ft (152cm)", True), ("> 30 cm", True), ("≤ 2 kg", True), ("&lt;5 kg", True),
     ("5ft (152cm)", False), ("30 cm <", False), ("approx. < 30 cm", False)],
)  # fmt: skip
def test_bound_value_is_a_sign_before_the_figure(value, bound):
    assert bound_value(value) is bound


def test_a_bound_is_no_height():
    assert _read(_row("Height", "<5ft (152cm)"), "Training Shorts", "en") is None
    assert _extents(_read(_row("Height", "5ft (152cm)"), "Training Shorts", "en")) == [152.0]


@pytest.mark.parametrize(
    ("value", "fluid"),
    [("4oz / 118ml / X Small", True), ("12 fl oz", True), ("8 oz (0.25 l)", True),
     ("4 oz", False), ("113 g (4 oz)", False), ("118 ml", False)],
)  # fmt: skip
def test_fluid_ounces_need_a_volume_beside_them(value, fluid):
    assert fluid_ounces(value) is fluid


def test_a_cups_ounces_beside_millilitres_are_no_weight():
    assert _read(_row("Weight", "4oz / 118ml"), "Reusable Cup", "en") is None
    assert _read(_row("Weight", "4 oz"), "Reusable Cup", "en").mass_g == pytest.approx(113.398, rel=1e-4)


# -- whose part a label names: the title's name ends at a bar; a part's head word --------------------------

TRAY = _row("Keyboard tray dimensions", '23.75 x 6.5"')


def test_a_part_the_titles_tagline_lists_stays_a_part():
    assert _read(TRAY, "Desk Converter | Compact, Adjustable Keyboard Tray", "en") is None
    assert _extents(_read(TRAY, "Adjustable Keyboard Tray | Shop", "en")) == [60.325, 16.51]


@pytest.mark.parametrize(
    ("part", "product"),
    [("this vase", True), ("vase", True), ("changedesk s top panel", False), ("top panel", False), (None, False)],
)  # fmt: skip
def test_a_part_names_the_product_by_its_head_word(part, product):
    assert _names_the_product(part, {"changedesk", "vase", "converter"}) is product


@given(st.text(max_size=60))
def test_bounds_and_fluid_ounces_never_raise(text):
    assert bound_value(text) in (True, False)
    assert fluid_ounces(text) in (True, False)
    if "oz" not in text.lower() and "ounce" not in text.lower():
        assert fluid_ounces(text) is False
    if not any(c.isdigit() for c in text):
        assert bound_value(text) is False
