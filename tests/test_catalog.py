import csv

import pytest

from kb.catalog import KnowledgeBase
from kb.csvio import write_catalog_csv
from kb.errors import CatalogImportError, DatabaseError, ObjectNotFound, QueryFailed, QueryRefused
from kb.features import ObjectRecord

HEADER = "name,a_cm,b_cm,c_cm,mass_g,shape,texture,fragility,material,rigidity"


def write(path, rows, header=HEADER):
    path.write_text("\n".join([header, *rows]) + "\n")
    return path


def test_import_is_all_or_nothing_and_names_row_column_reason(tmp_path, db_path):
    kb = KnowledgeBase.open(db_path)
    f = write(tmp_path / "bad.csv", [
        "calculator,15.4,7.9,1.5,116,thin,medium,medium,plastic,rigid",
        "mug,9.5,8,8,-300,prism,smooth,fragile,other,rigid",
        "pen,14,1,1,6,long,smooth,sturdy,plastic,wobbly",
    ])
    with pytest.raises(CatalogImportError) as info:
        kb.import_csv(f)
    assert info.value.problems == [
        (3, "mass_g", "must be greater than zero"),
        (4, "rigidity", "unknown rigidity; expected one of rigid, squeezable, floppy"),
    ]
    assert "row 3, column mass_g" in str(info.value)
    assert kb.count_objects() == 0  # nothing imported


def test_skip_invalid_imports_the_rest(tmp_path, db_path):
    kb = KnowledgeBase.open(db_path)
    f = write(tmp_path / "bad.csv", [
        "calculator,15.4,7.9,1.5,116,thin,medium,medium,plastic,rigid",
        ",9.5,8,8,300,prism,smooth,fragile,other,rigid",
    ])
    report = kb.import_csv(f, skip_invalid=True)
    assert report.new == ["calculator"]
    assert [(s.row, s.column) for s in report.skipped] == [(3, "name")]
    assert kb.count_objects() == 1


def test_reimport_changes_nothing_and_update_keeps_provenance(tmp_path, db_path):
    kb = KnowledgeBase.open(db_path)
    f = write(tmp_path / "a.csv", ["mug,9.5,8,8,300,prism,smooth,fragile,other,rigid"])
    assert kb.import_csv(f).new == ["mug"]
    before = kb.sql("select count(*) from observations").rows[0][0]
    second = kb.import_csv(f)
    assert (second.new, second.updated, second.unchanged) == ([], [], 1)
    assert kb.sql("select count(*) from observations").rows[0][0] == before
    g = write(tmp_path / "b.csv", ["mug,9.5,8,8,320,,,,,"])  # blank = unknown: keeps stored values
    assert kb.import_csv(g).updated == ["mug"]
    mug = kb.get_object("mug")
    assert mug.mass_g == 320 and mug.material == "other"
    masses = [p["value_num"] for p in kb.provenance("mug") if p["feature"] == "mass_g"]
    assert sorted(masses) == [300, 320]


def test_missing_header_column_is_named(tmp_path, db_path):
    kb = KnowledgeBase.open(db_path)
    f = write(tmp_path / "h.csv", ["x,1"], header="name,a_cm")
    with pytest.raises(CatalogImportError, match="column b_cm: missing column"):
        kb.import_csv(f)


def test_export_import_roundtrip(seeded_db, tmp_path):
    kb = KnowledgeBase.open(seeded_db)
    out = tmp_path / "export.csv"
    kb.export_csv(out)
    other = KnowledgeBase.open(tmp_path / "other.duckdb")
    assert len(other.import_csv(out).new) == kb.count_objects()
    assert other.list_objects() == kb.list_objects()
    assert kb.import_csv(out).unchanged == kb.count_objects()


def test_aliases_resolve_and_do_not_steal_names(tmp_path, db_path):
    kb = KnowledgeBase.open(db_path)
    recs = [
        ObjectRecord.create("tv remote", a_cm=16, b_cm=3.5, c_cm=2, aliases=["Remote Control", "pen"]),
        ObjectRecord.create("pen", a_cm=14, b_cm=1, c_cm=1),
    ]
    kb.upsert(recs, source="test", adapter="test")
    assert kb.get_object("remote  control").name == "tv remote"
    assert kb.get_object("pen").name == "pen"
    with pytest.raises(ObjectNotFound):
        kb.get_object("sofa")


def test_seed_catalog_has_paper_table_ii(seeded_db):
    kb = KnowledgeBase.open(seeded_db, read_only=True)
    assert kb.count_objects() >= 100
    ball = kb.get_object("tennis ball")
    assert (ball.a_cm, ball.b_cm, ball.c_cm, ball.mass_g, ball.rigidity) == (6.4, 6.4, 6.4, 56, "squeezable")


@pytest.mark.parametrize(
    "query",
    [
        "select * from read_csv('/etc/passwd')",
        "COPY objects TO '/tmp/objrecall-leak.csv'",
        "ATTACH '/tmp/objrecall-other.duckdb' AS other",
        "INSTALL httpfs",
        "LOAD httpfs",
        "DELETE FROM objects",
        "CREATE TABLE t(x INT)",
        "SET enable_external_access = true",
        "select 1; delete from objects",
    ],
)
def test_user_sql_is_sandboxed(seeded_db, query):
    kb = KnowledgeBase.open(seeded_db, read_only=True)
    with pytest.raises(QueryRefused):
        kb.sql(query)
    assert kb.count_objects() >= 100


def test_user_sql_limits(seeded_db):
    kb = KnowledgeBase.open(seeded_db, read_only=True)
    res = kb.sql("select name from objects order by name", max_rows=5)
    assert len(res.rows) == 5 and res.truncated
    with pytest.raises(QueryFailed, match="time limit"):
        kb.sql("select count(*) from range(1000000000000) a", timeout_s=0.5)
    with pytest.raises(QueryFailed, match="SQL error"):
        kb.sql("selec nonsense")
    frame = kb.sql("select name, mass_g from objects where shape = ?", ["radial"], output="pandas")
    assert list(frame.columns) == ["name", "mass_g"] and len(frame) > 3
    table = kb.sql("select name from objects limit 2", output="arrow")
    assert table.column_names == ["name"] and table.num_rows == 2
    for wrong in ("excel", "Pandas", "", None):  # an unknown output is refused, not answered in another form
        with pytest.raises(QueryFailed, match="unknown output"):
            kb.sql("select 1", output=wrong)


def test_reader_needs_existing_file(tmp_path):
    with pytest.raises(DatabaseError, match="objrecall init"):
        KnowledgeBase.open(tmp_path / "none.duckdb", read_only=True)


def test_hundred_row_csv(tmp_path, db_path):
    recs = [ObjectRecord.create(f"object {i}", a_cm=1 + i, b_cm=1, c_cm=0.5, mass_g=10 + i) for i in range(100)]
    f = tmp_path / "hundred.csv"
    write_catalog_csv(recs, f)
    assert len(list(csv.DictReader(f.open()))) == 100
    kb = KnowledgeBase.open(db_path)
    kb.import_csv(f)
    assert kb.sql("select count(*) as n from objects").to_dicts() == [{"n": 100}]


def test_no_connection_draws_a_progress_bar_and_the_lock_still_holds(tmp_path):
    """DuckDB draws a progress bar on stdout for any statement over 2 s (it corrupted ``--json`` output):
    every connection the catalog opens has it off, and user SQL's configuration lock still holds."""
    from kb.connections import open_connection
    from kb.sandbox import USER_SQL_CONFIG

    kb = KnowledgeBase.open(tmp_path / "c.duckdb")
    for write in (False, True):
        with kb.connect(write=write) as con:
            assert con.execute("SELECT current_setting('enable_progress_bar')").fetchone()[0] is False
    with kb.connect() as first, kb.connect() as second:  # two readers at once in one process (the service)
        for con in (first, second):
            assert con.execute("SELECT current_setting('enable_external_access')").fetchone()[0] is False
            assert con.execute("SELECT current_setting('enable_progress_bar')").fetchone()[0] is False
    con = open_connection(kb.path, read_only=True, config=USER_SQL_CONFIG)
    try:
        settings = dict(con.execute(
            "SELECT name, value FROM duckdb_settings() WHERE name IN "
            "('enable_progress_bar', 'lock_configuration', 'enable_external_access', 'threads')"
        ).fetchall())
    finally:
        con.close()
    assert settings == {"enable_progress_bar": "false", "lock_configuration": "true",
                        "enable_external_access": "false", "threads": "1"}


def test_a_missing_or_folder_file_is_named_as_such_never_row_0(tmp_path, db_path):
    """A file that cannot be read at all is the file's problem, not a row's: its message says what is wrong
    with the file (and the CLI's one line says the same), never "row 0, column -"."""
    from typer.testing import CliRunner

    from kb.service.cli import app

    kb = KnowledgeBase.open(db_path)
    missing = tmp_path / "nothere.csv"
    for path, why in [(missing, "no such file"), (tmp_path, "is a folder, not a CSV file")]:
        with pytest.raises(CatalogImportError) as info:
            kb.import_csv(path)
        assert str(info.value) == f"{path}: nothing imported: {why}"
        assert info.value.problems == [(0, "-", why)]
    res = CliRunner().invoke(app, ["catalog", "import", str(missing), "--db", str(db_path)])
    assert res.exit_code == 1 and res.stderr == f"Error: {missing}: nothing imported: no such file\n", res.stderr
    assert kb.count_objects() == 0


def test_a_whole_row_problem_names_the_row_and_a_cell_problem_its_column(tmp_path, db_path):
    f = write(tmp_path / "bad.csv", ["mug,9.5", "pen,14,1,1,-6,long,smooth,sturdy,plastic,rigid"])
    with pytest.raises(CatalogImportError) as info:
        KnowledgeBase.open(db_path).import_csv(f)
    assert str(info.value) == (f"{f}: nothing imported: row 2: 2 cells, header has 10; "
                               "row 3, column mass_g: must be greater than zero")
    with pytest.raises(CatalogImportError, match=r"nothing imported: row 1: empty file: no header$"):
        KnowledgeBase.open(db_path).import_csv(write(tmp_path / "empty.csv", [], header=""))
