import duckdb

from kb import migrate
from kb.schema import metadata


def columns(path):
    con = duckdb.connect(str(path), read_only=True)
    try:
        rows = con.execute(
            "select table_name, column_name from information_schema.columns where table_name <> 'alembic_version'"
        ).fetchall()
    finally:
        con.close()
    out = {}
    for table, col in rows:
        out.setdefault(table, set()).add(col)
    return out


def test_upgrade_downgrade_upgrade_keeps_rows(db_path):
    migrate.upgrade(db_path)
    assert migrate.current_revision(db_path) == migrate.head_revision()
    con = duckdb.connect(str(db_path))
    con.execute("insert into objects (name, a_cm, mass_g) values ('mug', 9.5, 300.25)")
    con.close()
    migrate.downgrade(db_path, "0001_catalog")
    assert migrate.current_revision(db_path) == "0001_catalog"
    assert "grasp_validations" not in columns(db_path)
    migrate.upgrade(db_path)
    con = duckdb.connect(str(db_path), read_only=True)
    assert con.execute("select name, a_cm, mass_g from objects").fetchall() == [("mug", 9.5, 300.25)]
    assert con.execute("select data_type from information_schema.columns where column_name='a_cm'").fetchone() == ("DOUBLE",)
    con.close()
    migrate.downgrade(db_path)
    assert columns(db_path) == {}
    migrate.upgrade(db_path)
    assert "objects" in columns(db_path)


def test_sqlalchemy_schema_mirrors_head(db_path):
    migrate.upgrade(db_path)
    actual = columns(db_path)
    expected = {t.name: {c.name for c in t.columns} for t in metadata.sorted_tables}
    assert actual == expected


def test_sequences_give_ids(db_path):
    migrate.upgrade(db_path)
    con = duckdb.connect(str(db_path))
    con.execute("insert into objects (name) values ('a'), ('b')")
    assert con.execute("select id from objects order by id").fetchall() == [(1,), (2,)]
    con.close()
