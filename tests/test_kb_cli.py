import json
import subprocess

from typer.testing import CliRunner

from kb import migrate
from kb.csvio import write_catalog_csv
from kb.features import ObjectRecord
from kb.service.cli import app

runner = CliRunner()


def run(*args):
    return runner.invoke(app, [str(a) for a in args])


def test_import_then_sql_count_json(tmp_path):
    db = tmp_path / "T.duckdb"
    csv = tmp_path / "X.csv"
    write_catalog_csv([ObjectRecord.create(f"thing {i}", a_cm=i + 1, mass_g=5) for i in range(100)], csv)
    res = run("catalog", "import", csv, "--db", db, "--json")
    assert res.exit_code == 0, res.output
    assert json.loads(res.stdout)["new"] == 100
    res = run("sql", "select count(*) as n from objects", "--db", db, "--json")
    assert json.loads(res.stdout)["rows"] == [{"n": 100}]


def test_init_seed_list_show_json(tmp_path):
    db = tmp_path / "c.duckdb"
    res = run("init", "--seed", "--db", db, "--json")
    info = json.loads(res.stdout)
    assert info["objects"] >= 100 and info["revision"] == migrate.head_revision()
    listed = json.loads(run("catalog", "list", "--db", db, "--json", "--limit", "5").stdout)
    assert len(listed) == 5 and all({"name", "a_cm", "shape"} <= set(o) for o in listed)
    shown = json.loads(run("catalog", "show", "Remote Control", "--db", db, "--json").stdout)
    assert shown["name"] == "tv remote" and shown["provenance"]
    summary = json.loads(run("catalog", "summary", "--db", db, "--json").stdout)
    assert summary["objects"] == info["objects"]


def test_errors_are_one_line_and_nonzero(tmp_path, cli_env):
    db = tmp_path / "c.duckdb"
    run("init", "--db", db)
    for args in (["sql", "select * from read_csv('/etc/passwd')"], ["sql", "COPY objects TO '/tmp/x.csv'"],
                 ["sql", "ATTACH '/tmp/y.duckdb'"], ["sql", "INSTALL httpfs"], ["catalog", "show", "sofa"]):
        out = subprocess.run(["objrecall", *args, "--db", str(db)], capture_output=True, text=True, env=cli_env)
        assert out.returncode == 1
        lines = out.stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("Error: "), out.stderr
        assert "Traceback" not in out.stderr


def test_bad_csv_reports_row_and_column(tmp_path):
    db = tmp_path / "c.duckdb"
    csv = tmp_path / "bad.csv"
    csv.write_text("name,a_cm,b_cm,c_cm,mass_g,shape,texture,fragility,material,rigidity\nmug,9,8,8,900000,,,,,\n")
    res = run("catalog", "import", csv, "--db", db)
    assert res.exit_code == 1
    assert "row 2, column mass_g" in res.output
    res = run("catalog", "import", csv, "--db", db, "--skip-invalid", "--json")
    assert json.loads(res.stdout)["skipped"][0]["column"] == "mass_g"


def test_export_to_file(tmp_path):
    db = tmp_path / "c.duckdb"
    run("init", "--seed", "--db", db)
    out = tmp_path / "e.csv"
    res = run("catalog", "export", out, "--db", db, "--json")
    assert json.loads(res.stdout)["objects"] >= 100
    assert out.read_text().startswith("name,a_cm,b_cm,c_cm,mass_g,shape,texture,fragility,material,rigidity")


def _objrecall(cli_env, *args, columns=80):
    env = {**cli_env, "COLUMNS": str(columns)}
    return subprocess.run(["objrecall", *map(str, args)], capture_output=True, text=True, env=env, timeout=120)


def test_catalog_list_is_readable_at_80_columns(tmp_path, cli_env):
    db = tmp_path / "c.duckdb"
    assert _objrecall(cli_env, "init", "--seed", "--db", db).returncode == 0
    out = _objrecall(cli_env, "catalog", "list", "--db", db).stdout
    assert max(len(line) for line in out.splitlines()) <= 80
    assert "…" not in out  # no cell cut short
    words = set(out.replace("│", " ").split())
    for name in ("adjustable wrench", "tennis ball", "tv remote"):  # whole, though a long name may wrap
        assert set(name.split()) <= words, name
    assert "6.4x6.4x6.4" in out  # the tennis ball's size on one line
    wide = _objrecall(cli_env, "catalog", "list", "--db", db, columns=200).stdout
    assert "fragility" in wide and "…" not in wide


def test_catalog_show_prints_each_source_once_and_suggests_names(tmp_path, cli_env):
    db = tmp_path / "c.duckdb"
    assert _objrecall(cli_env, "init", "--seed", "--db", db).returncode == 0
    out = _objrecall(cli_env, "catalog", "show", "tv remote", "--db", db, columns=200).stdout
    assert out.count("paper section IV-E") == 2  # the object's source row and one provenance heading
    missing = _objrecall(cli_env, "catalog", "show", "tv remot", "--db", db)
    assert missing.returncode == 1 and "did you mean 'tv remote'" in missing.stderr


def test_markup_in_names_is_shown_as_text(tmp_path, cli_env):
    db = tmp_path / "c.duckdb"
    evil = "[bold red]boom[/bold red] <script>alert(1)</script>"
    csv = tmp_path / "evil.csv"
    write_catalog_csv([ObjectRecord.create(evil, a_cm=3, mass_g=5)], csv)
    assert _objrecall(cli_env, "catalog", "import", csv, "--db", db).returncode == 0
    shown = _objrecall(cli_env, "catalog", "list", "--db", db, columns=200).stdout
    assert "[bold red]boom[/bold red]" in shown
    sql = _objrecall(cli_env, "sql", "select name as \"[i]n[/i]\" from objects", "--db", db, columns=200).stdout
    assert "[i]n[/i]" in sql and "[bold red]boom[/bold red]" in sql
