"""ids.csv and floors.csv beside an imported catalog (recall.catalog_folder), and the real catalogs."""

from pathlib import Path

import pytest

from kb.errors import RecallError
from recall.catalog_folder import read_floors, read_ids

DATA = Path(__file__).parent / "data"


def _folder(tmp_path, **files):
    for name, text in files.items():
        (tmp_path / f"{name}.csv").write_text(text, encoding="utf-8")
    return tmp_path / "catalog.csv"


def test_absent_files_mean_no_ids_and_no_floors(tmp_path):
    catalog = _folder(tmp_path)
    assert read_ids(catalog) == {} and read_floors(catalog) == {}


def test_ids_map_to_normalized_names(tmp_path):
    catalog = _folder(tmp_path, ids="id,name\n003_cracker_box,Cracker Box\n")
    assert read_ids(catalog) == {"003_cracker_box": "cracker box"}


@pytest.mark.parametrize(
    "text, reason",
    [
        ("id,name\na,x\na,y\n", "given twice"),
        ("id,name\na,\n", "both needed"),
        ("ident,name\na,x\n", "needs the columns"),
    ],
)
def test_bad_ids_are_refused_with_row_and_reason(tmp_path, text, reason):
    with pytest.raises(RecallError, match=reason):
        read_ids(_folder(tmp_path, ids=text))


def test_floors_read_and_bad_floors_refused(tmp_path):
    assert read_floors(_folder(tmp_path, floors="feature,at_least\na_cm,15\nmass_g,1000\n")) == {
        "a_cm": 15.0, "mass_g": 1000.0
    }  # fmt: skip
    for text, reason in [
        ("feature,at_least\nmaterial,1\n", "no numeric feature"),
        ("feature,at_least\na_cm,big\n", "not a number"),
        ("feature,at_least\na_cm,0\n", "one positive floor"),
        ("feature,at_least\na_cm,15\na_cm,16\n", "one positive floor"),
    ]:
        with pytest.raises(RecallError, match=reason):
            read_floors(_folder(tmp_path, floors=text))


@pytest.mark.parametrize("name", ["catalog_ycb", "catalog_yale"])
def test_the_real_catalogs_name_every_id_and_their_sources(name):
    import csv

    catalog = DATA / name / "catalog.csv"
    rows = list(csv.DictReader(catalog.open(encoding="utf-8")))
    ids = read_ids(catalog)
    assert sorted(set(ids.values())) == sorted(r["name"] for r in rows)
    assert all(r["source"].strip() for r in rows)
    for r in rows:
        sizes = [float(r[k]) for k in ("a_cm", "b_cm", "c_cm") if r[k]]
        assert sizes == sorted(sizes, reverse=True), r["name"]


def test_description_sets_may_label_objects_by_the_data_sets_id(tmp_path):
    from recall.evaluation import read_descriptions

    path = tmp_path / "d.csv"
    path.write_text('id,description\n003_cracker_box,"a box, 21 cm"\n', encoding="utf-8")
    assert read_descriptions(path) == [("003_cracker_box", "a box, 21 cm")]
