"""Batch report: HTML with rates, plots and images, JSON/CSV twins, and every scraped text escaped."""

from __future__ import annotations

import csv
import datetime as dt
import json
from html.parser import HTMLParser

import pytest

from sim.report import success_rates, write_report
from sim.worker import image_name

EVIL = "<script>alert(1)</script>"
PNG_1PX = bytes.fromhex(
    "89504e470d0a1a0a0000000d49484452000000010000000108060000001f15c489"
    "0000000d49444154789c63000100000500010d0a2db40000000049454e44ae426082"
)


def row(name, grasp, family, outcome, *, rank=0, shape="prism", material="plastic", image=None, reason=None):
    details = {"plan": {"grasp_type": grasp}}
    if image:
        details["image"] = image
    return {
        "object_name": name, "grasp_type": grasp, "family": family, "rank": rank, "seed": 0,
        "outcome": outcome, "success": outcome == "success", "reason": reason, "slip_cm": 0.42,
        "rotation_deg": 3.0, "grip_force_n": 5.5, "max_contact_force_n": 12.0, "simulator": "mujoco 3",
        "hand_version": "ar10like-1", "planner_version": "1", "features_hash": "abc",
        "details": json.dumps(details), "shape": shape, "material": material,
    }  # fmt: skip


@pytest.fixture
def rows():
    return [
        row("tennis ball", "power_sphere", "power", "success", shape="radial", material="fabric",
            image=image_name("tennis ball", "power_sphere")),
        row("tennis ball", "precision_sphere", "precision", "failure", rank=1, shape="radial", material="fabric"),
        row("tv remote", "thumb_4_finger", "precision", "success", shape="long"),
        row("tv remote", "light_tool", "power", "error", rank=1, shape="long", reason="diverged"),
        row(EVIL, "medium_wrap", "power", "failure", reason=f"slipped {EVIL}", material=EVIL),
    ]  # fmt: skip


class _Collector(HTMLParser):
    def __init__(self):
        super().__init__()
        self.scripts = 0
        self.imgs: list[str] = []

    def handle_starttag(self, tag, attrs):
        if tag == "script":
            self.scripts += 1
        if tag == "img":
            self.imgs.append(dict(attrs)["src"])


def test_success_rates_group_and_count():
    rates = success_rates(
        [{"k": "a", "outcome": "success"}, {"k": "a", "outcome": "failure"}, {"k": None, "outcome": "error"}],
        "k",
    )
    assert rates == [
        {"k": "a", "trials": 2, "success": 1, "failure": 1, "error": 0, "rate": 0.5},
        {"k": "unknown", "trials": 1, "success": 0, "failure": 0, "error": 1, "rate": 0.0},
    ]


def test_report_has_rates_plots_table_images_and_twins(rows, tmp_path):
    (tmp_path / "images").mkdir()
    (tmp_path / "images" / image_name("tennis ball", "power_sphere")).write_bytes(PNG_1PX)
    index = write_report(rows, tmp_path, now=lambda: dt.datetime(2026, 1, 2, 3, 4, tzinfo=dt.UTC))
    assert index == tmp_path / "index.html"
    page = index.read_text()
    assert "2026-01-02 03:04 UTC" in page and "5 trials" in page
    parser = _Collector()
    parser.feed(page)
    assert parser.scripts == 0
    for name in ("rates_by_grasp_type.png", "rates_by_shape.png", "rates_by_material.png"):
        assert name in parser.imgs
        assert (tmp_path / name).read_bytes()[:8] == PNG_1PX[:8]
    assert f"images/{image_name('tennis ball', 'power_sphere')}" in parser.imgs
    assert page.count("no image rendered") == 2  # tv remote and the evil object have none
    assert page.count("<tr><td>") >= 5

    data = json.loads((tmp_path / "results.json").read_text())
    assert (
        data["summary"]["trials"] == 5 and data["summary"]["success"] == 2 and data["summary"]["error"] == 1
    )
    by_type = {r["grasp_type"]: r for r in data["rates"]["grasp_type"]}
    assert by_type["power_sphere"]["rate"] == 1.0 and by_type["precision_sphere"]["rate"] == 0.0
    assert {r["shape"] for r in data["rates"]["shape"]} == {"radial", "long", "prism"}

    with (tmp_path / "results.csv").open(newline="") as fh:
        table = list(csv.DictReader(fh))
    assert len(table) == 5
    assert {r["object_name"] for r in table} >= {"tennis ball", "tv remote", EVIL}


def test_scraped_text_is_escaped_everywhere(rows, tmp_path):
    page = write_report(rows, tmp_path).read_text()
    assert EVIL not in page
    assert "&lt;script&gt;alert(1)&lt;/script&gt;" in page
    parser = _Collector()
    parser.feed(page)
    assert parser.scripts == 0


def test_image_names_from_rows_cannot_escape_the_images_folder(tmp_path):
    bad = row("x", "power_sphere", "power", "success", image="../../etc/passwd.png")
    bad_quote = row("y", "power_sphere", "power", "success", image="a' onerror='alert(1).png")
    page = write_report([bad, bad_quote], tmp_path).read_text()
    assert "passwd" not in page and "onerror" not in page


def test_csv_cells_cannot_become_formulas(tmp_path):
    write_report([row('=HYPERLINK("http://x")', "power_sphere", "power", "success")], tmp_path)
    with (tmp_path / "results.csv").open(newline="") as fh:
        (line,) = list(csv.DictReader(fh))
    assert line["object_name"].startswith("'=")


def test_empty_results_still_make_a_page(tmp_path):
    page = write_report([], tmp_path).read_text()
    assert "No trials." in page
    assert json.loads((tmp_path / "results.json").read_text())["summary"]["trials"] == 0


def test_report_shows_first_and_validated_choice_and_why_nothing_holds(tmp_path):
    (tmp_path / "images").mkdir()
    img_first, img_val = image_name("remote", "thumb_4_finger"), image_name("remote", "medium_wrap")
    for name in (img_first, img_val):
        (tmp_path / "images" / name).write_bytes(PNG_1PX)
    wide = row("soccer ball", "power_sphere", "power", "failure", reason="hand starts inside the object (3 mm)")
    heavy = row("anvil", "thumb_2_finger", "precision", "failure", reason="slipped 9 cm")
    heavy["details"] = json.dumps({"plan": {"params": {"force_within_capacity": False, "required_force_n": 80,
                                                       "friction": 0.4}}})  # fmt: skip
    rows = [
        row("remote", "thumb_4_finger", "precision", "failure", reason="turned 25.8 deg", image=img_first),
        row("remote", "medium_wrap", "power", "success", rank=1, image=img_val),
        wide, heavy,
    ]  # fmt: skip
    index = write_report(rows, tmp_path)
    page = index.read_text()
    assert "first choice" in page and "validated choice (planner&#x27;s rank 2)" in page
    assert f"images/{img_first}" in page and f"images/{img_val}" in page
    assert "no candidate holds" in page
    assert "aperture: the hand, opened for a" in page and "cannot get round it" in page  # the soccer ball: why
    assert "mass: holding it needs a squeeze of 80 N, more than the 30 N a thumb 2 finger gives" in page  # the anvil
    # the soccer ball started inside: a setup failure, counted apart from the two grasps that failed
    assert "grasp failure<b>2</b>" in page and "setup failure (aperture)<b>1</b>" in page
    doc = json.loads((tmp_path / "results.json").read_text())
    assert doc["summary"]["choices"] == {"objects": 3, "first_holds": 0, "validated": 1, "differs": 3}
    remote = next(c for c in doc["choices"] if c["object_name"] == "remote")
    assert (remote["first"], remote["validated"], remote["differs"]) == ("thumb_4_finger", "medium_wrap", True)


def test_the_report_says_which_protocol_judged_the_trials(tmp_path, rows):
    """Rows without a protocol are today's (lift_push); a six_direction row says so in the page, the JSON
    summary and each CSV row."""
    plain = write_report(rows, tmp_path / "plain").read_text()
    assert "protocol lift_push" in plain and "six_direction" not in plain
    six = [row("small cube", "medium_wrap", "power", "success")]
    six[0]["details"] = json.dumps({"plan": {}, "protocol": "six_direction"})
    page = write_report(six, tmp_path / "six").read_text()
    assert "protocol six_direction" in page and "lift_push" not in page
    summary = json.loads((tmp_path / "six" / "results.json").read_text())["summary"]
    assert summary["protocols"] == ["six_direction"]
    with (tmp_path / "six" / "results.csv").open(newline="") as fh:
        assert [r["protocol"] for r in csv.DictReader(fh)] == ["six_direction"]
