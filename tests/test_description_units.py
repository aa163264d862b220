"""Every unit word a description may use is read or reported, never dropped (kb.measures.units.description_units,
recall/unread.py): "a 40 tonne mug" and "a 3 km long pencil" are refused as absurd with the reason "600 kg"
gets, a number followed by a word the parser does not know is listed as not read, and either lowers the
confidence. All texts written here."""

from __future__ import annotations

import json

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from pytest import approx
from typer.testing import CliRunner

from kb.features import MAX_DIM_CM, MAX_MASS_G
from kb.measures.units import description_units
from kb.service.cli import app
from recall.confidence import REFUSED_CONFIDENCE_CAP
from recall.engine import Recaller
from recall.parser import parse
from recall.unread import UNREAD_REASON

_ABSURD = "absurd for a household object"


@pytest.mark.parametrize(
    ("text", "feature", "value"),
    [
        ("a mug of 0.5 tonne", "mass_g", 500_000.0), ("a 300 Gramm mug", "mass_g", 300.0),
        ("a 2 kilogramos box", "mass_g", 2000.0), ("a 300 grammes mug", "mass_g", 300.0),
        ("a 2 kilogrammes mug", "mass_g", 2000.0), ("a 12 Zentimeter long pencil", "a_cm", 12.0),
        ("a rope 0.005 km long", "a_cm", 500.0), ("a 2 yd long rope", "a_cm", 182.88),
        ("a hose 0.1 km long", "a_cm", 500.0),  # a long thing's length up to 100 m: at least 5 m (PARSER.md)
        ("a sheet 50 µm thick, 20 cm long", "c_cm", 0.005), ("a 1 stone 3 lb bag", "mass_g", 7711.0703),
    ],
)  # fmt: skip
def test_the_units_people_use_are_read(text: str, feature: str, value: float) -> None:
    parsed = parse(text)
    assert parsed.values()[feature] == approx(value, rel=1e-6) and not parsed.refused


@pytest.mark.parametrize(
    "text",
    ["a 40 tonne mug", "a 2 t mug", "a mug of 0.6 tonnes", "a 3 km long pencil", "a ball 0.006 km wide",
     "a 6 yd wide rug", "a 1 mi long pencil", "a 600 kg mug", "a 100 stone mug", "a hose 0.11 km long"],
)  # fmt: skip
def test_absurd_values_in_any_unit_are_refused_with_the_600_kg_reason(text: str) -> None:
    parsed = parse(text)
    assert "mass_g" not in parsed.values() and "a_cm" not in parsed.values()
    assert len(parsed.refused) == 1 and _ABSURD in parsed.refused[0].reason


def test_english_words_and_letter_compounds_stay_words() -> None:
    assert parse("a 5 t-shirt").refused == () and parse("a stone mortar").values() == {"material": "other"}
    assert parse("a 2 l-shaped bracket").refused == ()
    assert parse("a 5 m-long rope").values()["a_cm"] == 500.0  # a dimension word after the hyphen splits
    assert parse("300g-ish").values()["mass_g"] == 300.0  # glued to its number: "-ish" is a hedge
    assert parse("a 3 once bottle").refused[0].reason == UNREAD_REASON  # "once": English, no ounce


@settings(max_examples=150, deadline=None)
@given(st.sampled_from(sorted(w for w in description_units() if w.isalpha() and len(w) > 1)),
       st.integers(min_value=1, max_value=10**6))  # fmt: skip
def test_a_number_and_any_unit_word_is_used_or_refused_never_dropped(word: str, n: int) -> None:
    unit = description_units()[word]
    parsed = parse(f"an object of {n} {word}")
    feature = {"length": "a_cm", "mass": "mass_g", "volume": None}[unit.kind]
    if feature is None:
        return  # a volume outside a contents sentence states no feature (recall/PARSER.md)
    used = feature in parsed.values()
    assert used != bool(parsed.refused), (parsed.values(), parsed.refused)
    limit = MAX_DIM_CM if feature == "a_cm" else MAX_MASS_G
    if used:
        assert parsed.values()[feature] == approx(min(n * unit.factor, limit), rel=1e-3)
    else:
        assert n * unit.factor > limit or n * unit.factor < 1e-4
    assert parsed.values().get(feature, 0) <= limit


@pytest.mark.parametrize("text", ["a 40 blorps mug", "a mug, 10 cm tall, 40 blorps", "a 60 watt bulb, 8 cm"])
def test_a_number_and_an_unknown_word_is_reported_not_read(text: str) -> None:
    refused = parse(text).refused
    assert [r.reason for r in refused] == [UNREAD_REASON]
    assert refused[0].words.split()[0].isdigit()


@pytest.mark.parametrize("text", ["a set of 3 spoons", "a 2nd mug", "a 1920s lamp", "a 9v battery",
                                  "two handles, 20 cm long", "a 2 pack of cups"])  # fmt: skip
def test_counts_ordinals_and_number_words_are_not_unread_values(text: str) -> None:
    assert parse(text).refused == ()


@pytest.fixture(scope="module")
def recaller(tmp_path_factory) -> Recaller:
    db = tmp_path_factory.mktemp("units") / "seed.duckdb"
    res = CliRunner().invoke(app, ["init", "--seed", "--db", str(db)])
    assert res.exit_code == 0, res.output
    return Recaller.from_db(db)


def test_a_refused_or_unread_value_caps_the_confidence(recaller: Recaller) -> None:
    plain = recaller.recall_text("a coffee mug 10 cm tall")
    assert plain.confidence > REFUSED_CONFIDENCE_CAP
    for text in ("a coffee mug 10 cm tall, 40 tonnes", "a coffee mug 10 cm tall, 40 blorps",
                 "a 40 tonne coffee mug", "a 3 km long pencil"):  # fmt: skip
        res = recaller.recall_text(text)
        assert res.confidence <= REFUSED_CONFIDENCE_CAP and res.parsed["refused"], text
    # a word the catalog's names hold is no unread value ("2 AA batteries": the catalog's "aa battery")
    res = recaller.recall_text("2 AA batteries")
    assert res.parsed["refused"] == [] and res.confidence > REFUSED_CONFIDENCE_CAP


def test_the_cli_reports_the_unread_and_the_absurd(recaller: Recaller, tmp_path) -> None:
    db = tmp_path / "x.duckdb"
    assert CliRunner().invoke(app, ["init", "--seed", "--db", str(db)]).exit_code == 0
    res = CliRunner().invoke(app, ["recall", "a 40 blorps mug", "--db", str(db)])
    assert res.exit_code == 0 and "'40 blorps'" in res.stdout and "not read" in res.stdout
    out = json.loads(CliRunner().invoke(app, ["recall", "a 40 tonne mug", "--db", str(db), "--json"]).stdout)
    assert _ABSURD in out["parsed"]["refused"][0]["reason"] and out["confidence"] <= REFUSED_CONFIDENCE_CAP
