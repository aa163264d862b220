"""scripts/label_agreement.py: two labellings of the real-page corpus compared page by page (dims: same
number of extents, each within 2 %; mass: within 2 % or both null). Label sets written here."""

from __future__ import annotations

import importlib.util
import json
import subprocess
import sys
from pathlib import Path

from hypothesis import given
from hypothesis import strategies as st

REPO = Path(__file__).resolve().parents[1]
SCRIPT = REPO / "scripts" / "label_agreement.py"
_spec = importlib.util.spec_from_file_location("label_agreement", SCRIPT)
agreement = importlib.util.module_from_spec(_spec)
sys.modules["label_agreement"] = agreement  # dataclasses look their module up
_spec.loader.exec_module(agreement)


def test_exactly_two_percent_of_the_larger_agrees_and_a_hair_more_does_not():
    assert agreement.within(100.0, 98.0)
    assert agreement.within(98.0, 100.0)
    assert not agreement.within(100.0, 97.99)
    assert agreement.within(50.0, 51.0)  # 1 is 1.96 % of 51
    assert not agreement.within(50.0, 51.03)


def test_dims_need_the_same_number_of_extents_each_within_two_percent():
    assert agreement.dims_agree(None, None)
    assert not agreement.dims_agree([10.0], None)
    assert not agreement.dims_agree(None, [10.0])
    assert agreement.dims_agree([38.1, 26.04, 7.62], [7.62, 38.1, 26.04])  # order does not matter
    assert not agreement.dims_agree([22.86, 22.86, 5.08], [22.86, 5.08])  # a diameter counted once
    assert agreement.dims_agree([100.0, 50.0], [98.0, 50.0])
    assert not agreement.dims_agree([100.0, 50.0], [100.0, 48.9])


def test_mass_agrees_within_two_percent_or_when_both_are_null():
    assert agreement.mass_agrees(None, None)
    assert not agreement.mass_agrees(None, 127.6)
    assert not agreement.mass_agrees(402.0, None)
    assert agreement.mass_agrees(1000.0, 980.0)
    assert not agreement.mass_agrees(1000.0, 979.0)


finite = st.floats(min_value=0.01, max_value=1e5, allow_nan=False)


@given(st.lists(finite, min_size=1, max_size=3), st.lists(finite, min_size=1, max_size=3))
def test_dims_agreement_is_symmetric_and_reflexive(a, b):
    assert agreement.dims_agree(a, a)
    assert agreement.dims_agree(a, b) == agreement.dims_agree(b, a)


def _write(path: Path, rows: list[dict]) -> Path:
    path.write_text("".join(json.dumps(r) + "\n" for r in rows), encoding="utf-8")
    return path


def test_the_script_prints_both_rates_and_every_disagreement(tmp_path):
    first = _write(tmp_path / "first.jsonl", [
        {"id": "p1", "dims_cm": [100.0, 50.0], "mass_g": 1000.0},
        {"id": "p2", "dims_cm": [20.0], "mass_g": None},
        {"id": "p3", "dims_cm": None, "mass_g": 127.6},
        {"id": "p4", "dims_cm": [10.0, 10.0, 2.0], "mass_g": 50.0},
    ])
    second = _write(tmp_path / "second.jsonl", [
        {"id": "p1", "dims_cm": [98.0, 50.0], "mass_g": 980.0},  # both at exactly 2 %: agree
        {"id": "p2", "dims_cm": [20.0], "mass_g": None},
        {"id": "p3", "dims_cm": None, "mass_g": None, "resolution": "second"},
        {"id": "p4", "dims_cm": [10.0, 2.0], "mass_g": 48.9},
        {"id": "p5", "dims_cm": None, "mass_g": None},
    ])
    out = subprocess.run([sys.executable, str(SCRIPT), "--first", str(first), "--second", str(second)],
                         capture_output=True, text=True, check=True, cwd=tmp_path).stdout
    assert "pages compared: 5" in out
    assert "dims agree: 3/5 (0.60)" in out
    assert "mass agrees: 2/5 (0.40)" in out
    assert "disagreements: 3" in out
    assert "p1" not in out and "p2" not in out
    assert "p3 mass: first 127.6 second None" in out
    assert "p3 dims" not in out
    assert "resolution: second" in out
    assert "p4 dims: first [10.0, 10.0, 2.0] second [10.0, 2.0]" in out
    assert "p4 mass: first 50.0 second 48.9" in out
    assert "p5: not in the first labelling" in out


def test_a_later_first_row_replaces_an_earlier_one_with_the_same_id():
    result = agreement.compare([{"id": "p", "mass_g": 10.0}, {"id": "p", "mass_g": 20.0}], [{"id": "p", "mass_g": 20.0}])
    assert result.mass_agreeing == 1
