"""ids.csv and floors.csv beside an imported catalog (recall.catalog_folder), and the real catalogs."""

from pathlib import Path

import pytest

from kb.errors import RecallError
from recall.catalog_folder import read_bins, read_floors, read_ids

DATA = Path(__file__).parent / "data"


def _folder(tmp_path, **files):
    for name, text in files.items():
        (tmp_path / f"{name}.csv").write_text(text, encoding="utf-8")
    return tmp_path / "catalog.csv"


def test_absent_files_mean_no_ids_and_no_floors(tmp_path):
    catalog = _folder(tmp_path)
    assert read_ids(catalog) == {} and read_floors(catalog) == {} and read_bins(catalog) == {}


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


def test_bins_read_and_bad_bins_refused(tmp_path):
    import math

    text = "feature,below,above\na_cm,1,inf\nmass_g,2,2\n"
    assert read_bins(_folder(tmp_path, bins=text)) == {"a_cm": (1.0, math.inf), "mass_g": (2.0, 2.0)}
    assert read_bins(_folder(tmp_path, bins="feature,below,above\nb_cm,1,1\n")) == {"b_cm": (1.0, 1.0)}
    for text, reason in [
        ("feature,below,above\nshape,1,1\n", "no numeric feature"),
        ("feature,below,above\na_cm,1,wide\n", "must be numbers"),
        ("feature,below,above\na_cm,0.99,2\n", "at least 1"),  # a class narrower than its value
        ("feature,below,above\na_cm,2,0.99\n", "at least 1"),
        ("feature,below,above\na_cm,inf,2\n", "below finite"),
        ("feature,below,above\na_cm,2,2\na_cm,3,3\n", "one class"),
        ("feature,below\na_cm,2\n", "needs the columns"),
    ]:
        with pytest.raises(RecallError, match=reason):
            read_bins(_folder(tmp_path, bins=text))


def test_the_yale_catalog_declares_its_classes():
    import math

    bins = read_bins(DATA / "catalog_yale" / "catalog.csv")
    assert bins["a_cm"] == bins["b_cm"] == bins["c_cm"] == (1.25, math.inf) and bins["mass_g"] == (1.5, 1.5)
    assert read_bins(DATA / "catalog_ycb" / "catalog.csv") == {}  # measured extents and masses


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


def test_the_verdict_reads_a_binned_catalogs_classes(tmp_path):
    """On the real Yale catalog, whose sizes are those of the part grasped (a drawer's: 15 x 8 x 1.5 cm):
    once the catalog's classes are read, the whole drawer's sizes rank the drawer first and fit it;
    without them the drawer is ranked below other objects (since the catalog's kind-named objects hold every
    noun of their kind, Yale's "furniture" is then the first match, and fits)."""
    from recall.evaluation import _recaller_from_catalog

    catalog = DATA / "catalog_yale" / "catalog.csv"
    recaller = _recaller_from_catalog(catalog, tmp_path)
    assert recaller.floors == read_floors(catalog) and recaller.bins == read_bins(catalog)
    recaller.bins = {}
    text = "a drawer out of a dresser, 40 cm wide, 35 cm deep, 15 cm high, about 3 kg"
    plain = recaller.recall_text(text, top=3)
    assert plain.matches[0].name != "drawer"
    recaller.bins = read_bins(catalog)  # read back, as the catalog's folder declares
    binned = recaller.recall_text(text, top=3)
    assert binned.matches[0].name == "drawer" and not binned.open_set
