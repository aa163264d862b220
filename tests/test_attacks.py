"""Outside attacks, replayed: hostile SQL, resource bombs, malformed CSVs, hostile descriptions, XSS in names.

Everything here is loopback only and bounded: every child process has a wall-clock timeout, resource bombs
are measured by the peak RSS of a child process (``resource.getrusage``) against a bound with a large
margin, and no assertion is about speed.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from kb import sandbox
from kb.catalog import KnowledgeBase
from kb.errors import QueryFailed, QueryRefused, QueryTimeout
from kb.features import ObjectRecord

REPO = Path(__file__).resolve().parents[1]

#: One statement of each class the outside review sent (file access, ATTACH, COPY, INSTALL/LOAD, SET,
#: PRAGMA, writes, multi-statements, UPDATE EXTENSIONS, functions revealing server paths).
HOSTILE_SQL = [
    "select * from read_csv('/etc/passwd')",
    "select * from read_text('/etc/passwd')",
    "select * from read_blob('/etc/hostname')",
    "select * from glob('/etc/*')",
    "select * from 'objects.csv'",
    "select * from read_csv('http://127.0.0.1:9/x.csv')",
    "COPY objects TO '{tmp}/leak.csv'",
    "COPY (select * from objects) TO '{tmp}/leak2.csv'",
    "COPY objects FROM '/etc/passwd'",
    "EXPORT DATABASE '{tmp}/export'",
    "IMPORT DATABASE '{tmp}/export'",
    "EXPLAIN ANALYZE COPY objects TO '{tmp}/leak3.csv'",
    "ATTACH '{tmp}/other.duckdb' AS other",
    "ATTACH ':memory:' AS m",
    "DETACH seeded",
    "USE memory",
    "INSTALL httpfs",
    "FORCE INSTALL httpfs",
    "LOAD httpfs",
    "LOAD '{tmp}/evil.duckdb_extension'",
    "UPDATE EXTENSIONS",
    "UPDATE EXTENSIONS (httpfs)",
    "SET enable_external_access = true",
    "SET threads = 64",
    "RESET memory_limit",
    "SET GLOBAL lock_configuration = false",
    "SET VARIABLE v = 1",
    "PRAGMA database_list",
    "PRAGMA enable_profiling",
    "CALL pragma_version()",
    "CHECKPOINT",
    "VACUUM",
    "BEGIN TRANSACTION",
    "INSERT INTO objects (name) VALUES ('evil')",
    "UPDATE objects SET name = 'evil'",
    "DELETE FROM objects",
    "TRUNCATE objects",
    "DROP TABLE objects",
    "ALTER TABLE objects RENAME TO gone",
    "CREATE TABLE t(x INT)",
    "CREATE TEMP TABLE t AS SELECT 1",
    "CREATE MACRO m() AS 1",
    "CREATE SECRET s (TYPE s3, KEY_ID 'x', SECRET 'y')",
    "select 1; delete from objects",
    "select 1; select 2",
    "select * from duckdb_databases()",
    'select path from "duckdb_databases"()',
    "select * from main.duckdb_databases()",
    "select * from pragma_database_list",
    "select * from duckdb_settings()",
    "select current_setting('temp_directory')",
    "select * from duckdb_extensions()",
    "select * from duckdb_secrets()",
    # settings through the pg_catalog view, and SQL built at run time that no text check can see into
    "select * from pg_catalog.pg_settings",
    "select * from pg_settings where setting like '%/%'",
    "select * from query('select * from duckdb_' || 'databases()')",
    'select * from "query" (\'select 1\')',
    "select * from QUERY_TABLE('objects')",
    "select json_execute_serialized_sql(json_serialize_sql('select 1'))",
]

#: The resource bombs of the review: each grew a process past 4 GB or ran past its timeout.
BOMBS = [
    "SELECT len(range(0, 3000000000))",
    "SELECT length(repeat('x', 2000000000))",
    "SELECT len(range(0, 500000000))",
    "select list(range) from range(300000000)",
]


def _sha(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def test_hostile_sql_is_refused_and_changes_nothing(seeded_db, tmp_path):
    kb = KnowledgeBase.open(seeded_db, read_only=True)
    before = _sha(seeded_db)
    for template in HOSTILE_SQL:
        query = template.format(tmp=tmp_path)
        with pytest.raises(QueryRefused) as err:
            kb.sql(query, timeout_s=5)
        message = str(err.value)
        assert "\n" not in message and "Traceback" not in message, query
        assert "refused" in message or "one statement" in message, (query, message)
        assert str(seeded_db.parent) not in message, (query, message)
    assert _sha(seeded_db) == before
    assert sorted(p.name for p in tmp_path.iterdir()) == [seeded_db.name]  # nothing written beside it


def test_an_unknown_statement_type_is_refused_not_a_crash(seeded_db):
    kb = KnowledgeBase.open(seeded_db, read_only=True)
    for query in ("UPDATE EXTENSIONS", "UPDATE EXTENSIONS (httpfs)"):
        with pytest.raises(QueryRefused, match="not allowed"):
            kb.sql(query)


def test_explain_runs_only_for_a_select(seeded_db):
    kb = KnowledgeBase.open(seeded_db, read_only=True)
    assert kb.sql("EXPLAIN SELECT count(*) FROM objects").rows
    with pytest.raises(QueryRefused, match="CREATE"):
        kb.sql("EXPLAIN CREATE TABLE x(y INT)")


def test_repeated_column_names_are_all_returned(seeded_db):
    kb = KnowledgeBase.open(seeded_db, read_only=True)
    res = kb.sql("SELECT 1 AS a, 2 AS a, 3 AS a, 4 AS b")
    assert res.columns == ["a", "a (2)", "a (3)", "b"]
    assert res.to_dicts() == [{"a": 1, "a (2)": 2, "a (3)": 3, "b": 4}]


def test_server_paths_do_not_come_back_from_metadata(seeded_db):
    kb = KnowledgeBase.open(seeded_db, read_only=True)
    # the database's name is fine (SHOW DATABASES), its folder is not
    names = kb.sql("SHOW DATABASES").rows
    assert str(seeded_db.parent) not in repr(names)
    with pytest.raises(QueryRefused, match="duckdb_databases"):
        kb.sql("SELECT path FROM duckdb_databases()")


def test_no_metadata_view_answers_with_a_server_path(seeded_db):
    """Every view and table function the sandbox lets through, asked for all its rows: none of them holds
    the catalog's folder (the pg_settings view did, through temp_directory and allowed paths)."""
    kb = KnowledgeBase.open(seeded_db, read_only=True)
    views = kb.sql(
        "SELECT schema_name || '.' || view_name FROM duckdb_views() WHERE database_name = 'system'", max_rows=10_000
    ).rows
    leaked = []
    for (view,) in views:
        try:
            rows = kb.sql(f"SELECT * FROM {view}", timeout_s=5, max_rows=10_000).rows
        except QueryRefused:
            continue
        if str(seeded_db.parent) in repr(rows):
            leaked.append(view)
    assert leaked == []


def test_words_that_name_dynamic_sql_are_fine_as_column_names(seeded_db):
    kb = KnowledgeBase.open(seeded_db, read_only=True)
    answer = kb.sql("SELECT name AS query, 1 AS query_table FROM objects ORDER BY name LIMIT 1")
    assert answer.columns == ["query", "query_table"] and len(answer.rows) == 1


_BOMB_RUNNER = textwrap.dedent(
    """
    import json, resource, sys
    from kb.catalog import KnowledgeBase
    from kb import sandbox
    kb = KnowledgeBase.open(sys.argv[1], read_only=True)
    out = []
    for query in sys.argv[2:]:
        try:
            kb.sql(query, timeout_s=5)
            out.append([query, "answered", ""])
        except Exception as err:
            out.append([query, type(err).__name__, str(err)])
    sandbox._POOL.close()  # wait for the workers, so their peak RSS is counted
    print(json.dumps({
        "results": out,
        "caller_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
        "workers_mb": resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024,
    }))
    """
)


def test_resource_bombs_are_refused_within_bounded_memory(seeded_db):
    """Each bomb is refused (memory or time limit) and neither the caller nor a worker grows past its
    bound; the review saw 4 GB to 24 GB and a kernel OOM kill for the same statements."""
    env = {**os.environ, "PYTHONPATH": str(REPO)}
    proc = subprocess.run(
        [sys.executable, "-c", _BOMB_RUNNER, str(seeded_db), *BOMBS],
        capture_output=True, text=True, timeout=180, env=env, cwd=REPO,
    )
    assert proc.returncode == 0, proc.stderr
    report = json.loads(proc.stdout.strip().splitlines()[-1])
    for query, kind, message in report["results"]:
        assert kind in ("QueryRefused", "QueryTimeout"), (query, kind, message)
        assert "memory" in message or "time limit" in message, (query, message)
    assert report["caller_mb"] < 1024, report
    assert report["workers_mb"] < 2048, report  # the worker's address space is capped at 1.5 GiB


def _running_workers() -> list[int]:
    """Sandbox worker processes of this process that are running (not sleeping on their next request)."""
    running = []
    for task in Path(f"/proc/{os.getpid()}/task").iterdir():
        for pid in (task / "children").read_text().split():
            try:
                cmdline = Path(f"/proc/{pid}/cmdline").read_bytes()
                state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
            except OSError:
                continue
            if b"kb.sandbox" in cmdline and state == "R":
                running.append(int(pid))
    return running


def test_a_timed_out_query_leaves_no_worker_running(seeded_db):
    kb = KnowledgeBase.open(seeded_db, read_only=True)
    kb.sql("SELECT 1")
    for query in ("SELECT length(repeat('x', 400000000))", "SELECT count(*) FROM range(1000000000000)"):
        with pytest.raises(QueryTimeout, match="time limit"):
            kb.sql(query, timeout_s=0.3)
        deadline = time.monotonic() + 10  # a bound on settling, not a speed claim
        while _running_workers() and time.monotonic() < deadline:
            time.sleep(0.05)
        assert _running_workers() == []
    assert kb.sql("SELECT count(*) FROM objects").rows[0][0] >= 100  # the sandbox works again after a kill


def test_sql_limits_are_checked_before_running(seeded_db):
    kb = KnowledgeBase.open(seeded_db, read_only=True)
    for bad in ({"timeout_s": 0}, {"timeout_s": -1}, {"max_rows": 0}, {"timeout_s": float("nan")},
                {"timeout_s": sandbox.MAX_TIMEOUT_S * 1.001}, {"timeout_s": 1e308}, {"timeout_s": float("inf")}):
        with pytest.raises(QueryFailed, match=f"{next(iter(bad))} must be"):  # the parameter at fault, named
            kb.sql("SELECT 1", **bad)
    assert kb.sql("SELECT 1", timeout_s=sandbox.MAX_TIMEOUT_S).rows == [(1,)]  # the limit itself is allowed


# ---------------------------------------------------------------------------------------------- malformed CSVs
_HEADER = "name,a_cm,b_cm,c_cm,mass_g,shape,texture,fragility,material,rigidity\n"
_GOOD = "mug,10,8,8,300,prism,smooth,fragile,glass,rigid\n"

#: (CSV text, row, column, words in the reason) of each malformed-file class the review sent.
MALFORMED_CSV = [
    (_HEADER + '"bowl,10,8,8,300,prism,smooth,fragile,glass,rigid\n' + _GOOD, 2, "-", "unbalanced quote"),
    (_HEADER + '"bowl,10,8,8,300,prism,smooth,fragile,glass,rigid\nbook",2,3,4,5,thin,smooth,sturdy,paper,rigid\n',
     2, "name", "spans several lines"),
    (_HEADER + "bowl," + "1" * 131_073 + ",8,8,300,prism,smooth,fragile,glass,rigid\n", 2, "-", "over 131,072"),
    (_HEADER + _GOOD + "bowl,nan,8,8,300,prism,smooth,fragile,glass,rigid\n", 3, "a_cm", "not a number"),
    (_HEADER + _GOOD + "bowl,NaN,8,8,300,prism,smooth,fragile,glass,rigid\n", 3, "a_cm", "not a number"),
    (_HEADER + _GOOD + "bowl,10,8,8,1_000,prism,smooth,fragile,glass,rigid\n", 3, "mass_g", "not a number"),
    (_HEADER + "bowl,10,8,8,inf,prism,smooth,fragile,glass,rigid\n", 2, "mass_g", "finite"),
    (_HEADER + "bowl,10,8,8,-Infinity,prism,smooth,fragile,glass,rigid\n", 2, "mass_g", "finite"),
    (_HEADER.strip() + ",mass_g\n" + _GOOD.strip() + ",5\n", 1, "mass_g", "more than once"),
    (_HEADER + "bowl,10,8\n", 2, "-", "3 cells, header has 10"),
    (_HEADER + _GOOD.strip() + ",extra\n", 2, "-", "11 cells, header has 10"),
    (_HEADER + "bo\x00wl,10,8,8,300,prism,smooth,fragile,glass,rigid\n", 2, "name", "NUL"),
    (_HEADER + "bowl,10,8,8,300,prism,smooth,fragile,gla\x00ss,rigid\n", 2, "material", "NUL"),
    (_HEADER + "bo\x07wl,10,8,8,300,prism,smooth,fragile,glass,rigid\n", 2, "name", "control characters"),
    (_HEADER + "x" * 201 + ",10,8,8,300,prism,smooth,fragile,glass,rigid\n", 2, "name", "implausible name"),
    ("", 1, "-", "empty file"),
    ("name,a_cm\nbowl,3\n", 1, "b_cm", "missing column"),
]


@pytest.mark.parametrize(("text", "row", "column", "reason"), MALFORMED_CSV)
def test_malformed_csv_is_refused_naming_row_column_reason(seeded_db, tmp_path, text, row, column, reason):
    from kb.errors import CatalogImportError

    path = tmp_path / "bad.csv"
    path.write_text(text, encoding="utf-8")
    kb = KnowledgeBase.open(seeded_db)
    before = kb.export_csv()
    with pytest.raises(CatalogImportError) as err:
        kb.import_csv(path)
    assert (row, column) in [(r, c) for r, c, _ in err.value.problems], err.value.problems
    assert any(reason in why for _, _, why in err.value.problems), err.value.problems
    assert "\n" not in str(err.value) and "nothing imported" in str(err.value)
    assert kb.export_csv() == before


def test_a_csv_that_cannot_be_read_is_one_clear_error(tmp_path):
    from kb.csvio import read_catalog_csv
    from kb.errors import CatalogImportError

    for path, why in ((tmp_path / "no-such.csv", "no such file"), (tmp_path, "is a folder")):
        with pytest.raises(CatalogImportError, match=why):
            read_catalog_csv(path)
    (tmp_path / "latin1.csv").write_bytes(b"name\n\xe9\n")
    with pytest.raises(CatalogImportError, match="not UTF-8"):
        read_catalog_csv(tmp_path / "latin1.csv")


def test_malformed_csv_via_the_cli_is_one_line_and_exit_1(tmp_path, cli_env):
    bad = tmp_path / "bad.csv"
    bad.write_text(MALFORMED_CSV[2][0], encoding="utf-8")  # the 131,073-character cell
    db = tmp_path / "c.duckdb"
    for args in (["catalog", "import", str(bad)],):
        proc = subprocess.run(["objrecall", *args, "--db", str(db)], capture_output=True, text=True,
                              env=cli_env, timeout=120)
        assert proc.returncode == 1, (args, proc.stdout, proc.stderr)
        lines = [ln for ln in (proc.stdout + proc.stderr).splitlines() if ln.strip()]
        assert len(lines) == 1 and "Traceback" not in lines[0] and "╭" not in lines[0], lines


_CSV_ALPHABET = st.sampled_from(list('abc ,;"\n\r\x00\t-.0123456789e') + ["nan", "inf", "mug", "prism", "glass"])


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(body=st.lists(_CSV_ALPHABET, max_size=80).map("".join))
def test_any_csv_text_is_read_or_refused_never_a_crash(body):
    from kb.csvio import parse_catalog_csv
    from kb.errors import CatalogImportError

    try:
        result = parse_catalog_csv(_HEADER + body)
    except CatalogImportError as err:
        assert err.problems and "\n" not in str(err)
        return
    for record in result.records:
        assert record.name and "\x00" not in record.name and "\n" not in record.name


# ---------------------------------------------------------------------------------------------- HTTP
def test_host_names_are_parsed_without_port():
    from kb.service.http.limits import host_name

    assert host_name(b"127.0.0.1:8000") == "127.0.0.1"
    assert host_name(b"LocalHost") == "localhost"
    assert host_name(b"[::1]:8000") == "::1"
    assert host_name(b"::1") == "::1"
    assert host_name(None) == ""


def test_only_allowed_host_headers_are_answered(seeded_db, monkeypatch):
    from fastapi.testclient import TestClient

    from kb.service.http import create_app

    monkeypatch.delenv("OBJRECALL_ALLOWED_HOSTS", raising=False)
    client = TestClient(create_app(seeded_db, token=""), base_url="http://127.0.0.1:8000")
    for host in ("127.0.0.1:8000", "localhost", "localhost:1234", "[::1]:8000"):
        assert client.get("/health", headers={"Host": host}).status_code == 200, host
    for host in ("evil.example", "evil.example:8000", "127.0.0.1.evil.example", "localhost.", ""):
        response = client.get("/objects", headers={"Host": host})
        assert response.status_code == 400, host
        assert response.json()["error"] == "BadRequest" and "Host" in response.json()["detail"]
    monkeypatch.setenv("OBJRECALL_ALLOWED_HOSTS", "objrecall.lan, 10.0.0.5")
    client = TestClient(create_app(seeded_db, token=""), base_url="http://objrecall.lan")
    assert client.get("/health").status_code == 200
    assert client.get("/health", headers={"Host": "localhost"}).status_code == 400
    anyhost = TestClient(create_app(seeded_db, token="", allowed_hosts=["*"]), base_url="http://whatever.example")
    assert anyhost.get("/health").status_code == 200


@pytest.fixture(scope="module")
def live_server(tmp_path_factory):
    """(base URL, server pid) of `objrecall serve` on loopback with a 1 s request-read deadline."""
    from kb.catalog import KnowledgeBase
    from kb.service.bootstrap import seed_catalog_path
    from kb.service.http import serve_subprocess

    db = tmp_path_factory.mktemp("attack") / "catalog.duckdb"
    KnowledgeBase.open(db).import_csv(seed_catalog_path())
    env = {**os.environ, "PYTHONPATH": str(REPO), "PATH": f"{Path(sys.executable).parent}:{os.environ['PATH']}"}
    env.pop("OBJRECALL_ALLOWED_HOSTS", None)
    with serve_subprocess(db, env=env, extra_args=["--header-timeout", "1", "--log-level", "warning"]) as base:
        port = int(base.rsplit(":", 1)[1])
        yield base, _listening_pid(port)


def _listening_pid(port: int) -> int:
    """The pid of the process listening on 127.0.0.1:port (via /proc)."""
    inode = None
    for line in Path("/proc/net/tcp").read_text().splitlines()[1:]:
        fields = line.split()
        if fields[1].endswith(f":{port:04X}") and fields[3] == "0A":
            inode = fields[9]
    assert inode is not None
    for proc in Path("/proc").iterdir():
        if not proc.name.isdigit():
            continue
        try:
            if any(os.readlink(fd) == f"socket:[{inode}]" for fd in (proc / "fd").iterdir()):
                return int(proc.name)
        except OSError:
            continue
    raise AssertionError("no listener found")


def _children(pid: int) -> list[int]:
    out = []
    for task in Path(f"/proc/{pid}/task").iterdir():
        out += [int(p) for p in (task / "children").read_text().split()]
    return out


def _peak_rss_mb(pid: int) -> float:
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmHWM:"):
            return int(line.split()[1]) / 1024
    return 0.0


@pytest.mark.slow
def test_half_open_connections_are_closed_and_the_server_keeps_answering(live_server):
    import socket

    import httpx

    base, _ = live_server
    port = int(base.rsplit(":", 1)[1])
    sockets = []
    try:
        for i in range(300):
            s = socket.create_connection(("127.0.0.1", port), timeout=10)
            if i % 3 == 1:  # headers that never finish
                s.sendall(b"GET /objects HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: ")
            elif i % 3 == 2:  # a body that never finishes
                s.sendall(b"POST /sql HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: 500\r\n\r\n{")
            sockets.append(s)  # and every third sends nothing at all
        assert httpx.get(f"{base}/health", timeout=30).status_code == 200  # served during the attack
        closed = 0
        deadline = time.monotonic() + 60  # a bound on the test, not a speed claim
        for s in sockets:
            s.settimeout(max(0.1, deadline - time.monotonic()))
            try:
                while s.recv(1024):
                    pass
                closed += 1
            except ConnectionResetError:
                closed += 1
            except TimeoutError:
                pass
        assert closed == len(sockets)
    finally:
        for s in sockets:
            s.close()
    assert httpx.get(f"{base}/objects?limit=1", timeout=30).status_code == 200


@pytest.mark.slow
def test_sql_bombs_over_http_are_refused_and_stop_with_their_request(live_server):
    import httpx

    base, pid = live_server
    for query in BOMBS[:3]:
        response = httpx.post(f"{base}/sql", json={"query": query, "timeout_s": 5}, timeout=120)
        assert response.status_code == 400 and "memory" in response.json()["detail"], (query, response.text)
    response = httpx.post(f"{base}/sql", json={"query": "SELECT length(repeat('x', 400000000))", "timeout_s": 0.5},
                          timeout=120)
    assert response.status_code == 504 and response.json()["error"] == "RequestTimeout"
    deadline = time.monotonic() + 10  # settling bound
    while time.monotonic() < deadline:
        states = [Path(f"/proc/{c}/stat").read_text().rsplit(")", 1)[1].split()[0] for c in _children(pid)]
        if "R" not in states:
            break
        time.sleep(0.05)
    assert "R" not in states  # no SQL worker keeps running after its 504
    assert _peak_rss_mb(pid) < 1536
    assert all(_peak_rss_mb(c) < 2048 for c in _children(pid))
    for query in ("SELECT 1 AS a, 2 AS a", "SELECT path FROM duckdb_databases()", "UPDATE EXTENSIONS"):
        response = httpx.post(f"{base}/sql", json={"query": query}, timeout=60)
        assert response.status_code in (200, 400), response.text
        assert str(Path(base).name) not in response.text
    both = httpx.post(f"{base}/sql", json={"query": "SELECT 1 AS a, 2 AS a"}, timeout=60).json()
    assert both["columns"] == ["a", "a (2)"] and both["rows"] == [{"a": 1, "a (2)": 2}]
    refused = httpx.post(f"{base}/sql", json={"query": "SELECT path FROM duckdb_databases()"}, timeout=60)
    assert refused.status_code == 400 and "/" not in refused.json()["detail"]
    unknown = httpx.post(f"{base}/sql", json={"query": "UPDATE EXTENSIONS (httpfs)"}, timeout=60)
    assert unknown.status_code == 400 and unknown.json()["error"] == "QueryRefused"


def test_api_docs_are_served_offline(seeded_db):
    """/docs and /redoc load every script and style from this server (no CDN: the page works offline)."""
    import re

    from fastapi.testclient import TestClient

    from kb.service.http import create_app

    client = TestClient(create_app(seeded_db, token=""), base_url="http://127.0.0.1")
    for page in ("/docs", "/redoc"):
        html = client.get(page).text
        assets = re.findall(r'(?:src|href)=["\']([^"\']+\.(?:js|css))["\']', html)
        assert assets, page
        for url in assets:
            assert url.startswith("/") and not url.startswith("//"), (page, url)
            response = client.get(url)
            assert response.status_code == 200 and len(response.content) > 1000, (page, url)
        assert "cdn." not in html and "https://" not in html.replace("https://swagger.io", ""), page
    assert client.get("/openapi.json").json()["paths"]


# ---------------------------------------------------------------------------------------------- XSS payloads
XSS = [
    "<script>alert(1)</script>",
    '"><img src=x onerror=alert(1)>',
    "<svg/onload=alert(1)>",
    "javascript:alert(1)",
    "</td></tr><script>alert(1)</script>",
    "{{7*7}} ${7*7} <%= 7*7 %>",
]


def test_xss_payloads_round_trip_as_data_over_http(tmp_path):
    from urllib.parse import quote

    from fastapi.testclient import TestClient

    from kb.service.http import create_app

    db = tmp_path / "c.duckdb"
    KnowledgeBase.open(db).upsert([ObjectRecord.create("plain mug", a_cm=10, mass_g=300)], source="t", adapter="t")
    client = TestClient(create_app(db, token="tok"), base_url="http://127.0.0.1")
    auth = {"Authorization": "Bearer tok"}
    for i, payload in enumerate(XSS):
        name = f"thing {i} {payload}"  # "/" included: the name is the rest of the path ({name:path})
        body = {"a_cm": 3, "mass_g": 12, "aliases": [f"alias {i} {payload}"], "source": f"https://x/{payload}"}
        put = client.put(f"/objects/{quote(name, safe='')}", json=body, headers=auth)
        assert put.status_code in (200, 201), (payload, put.text)
        got = client.get("/objects", params={"limit": 500})
        assert got.headers["content-type"].startswith("application/json")
        assert got.headers["x-content-type-options"] == "nosniff"
        stored = {o["name"]: o for o in got.json()["items"]}
        key = " ".join(name.lower().split())
        assert key in stored and stored[key]["source"] == body["source"], payload
    page = client.get("/")
    assert "script-src 'self'" in page.headers["content-security-policy"]  # no inline script can run


def test_xss_payloads_are_escaped_in_the_grasp_report(tmp_path):
    from sim.report import write_report

    rows = [{"object_name": f"obj {p}", "grasp_type": "power", "family": "power", "rank": 1, "seed": 0,
             "outcome": "failure", "reason": p, "success": False} for p in XSS]
    html = write_report(rows, tmp_path / "report").read_text()
    for payload in XSS:
        if "<" in payload or '"' in payload:
            assert payload not in html, payload
    assert "<script>alert(1)</script>" not in html and "&lt;script&gt;" in html


# ---------------------------------------------------------------------------------------------- descriptions
HOSTILE_DESCRIPTIONS = [
    "", " ", "\x00", "\x00" * 50, "\u202e\u202d mug", "🦆" * 300, "a" * 4999, "x " * 2500,
    "'; DROP TABLE objects; --", "\" OR 1=1 --", "<script>alert(1)</script> mug",
    "-10 kg", "-5 cm long", "1e308 cm", "10**100 g", "NaN cm", "inf kg", "0 g", "0.0000001 mm",
    "9" * 400 + " cm", "1/0 inches", "3 ft 12 in", "5 feet 13 inches", "--- --- ---", "....", "%s%s%n%x",
    "\n\n\n\t\t", "mug" * 1000, "a mug " * 800, "ｍｕｇ １０ ｃｍ", "ＡＢＣ", "a\u0301" * 100,
    "a 500 kg 5 m tall box", "a 500.0001 kg box", "a 50000 cm box", "between 3 and 2 cm", "from 5 to cm",
]


def test_hostile_descriptions_never_crash_recall(seeded_db):
    from hypothesis import HealthCheck, given, settings
    from hypothesis import strategies as st

    from kb.errors import ObjrecallError
    from recall.engine import Recaller

    recaller = Recaller.from_db(seeded_db)

    def check(text: str) -> None:
        try:
            result = recaller.recall_text(text, top=3)
        except ObjrecallError as err:  # a clear refusal (empty, too long) is fine
            assert str(err) and "\n" not in str(err).strip()
            return
        assert 0.0 <= result.confidence <= 1.0
        for match in result.matches:
            assert math.isfinite(match.distance)

    for text in HOSTILE_DESCRIPTIONS:
        check(text)

    @settings(max_examples=300, deadline=None, suppress_health_check=list(HealthCheck))
    @given(st.text(max_size=200) | st.lists(st.sampled_from(
        ["mug", "-", "1e9", "kg", "cm", "ft", "in", "12", "'", "3/4", "x", "by", "about", "nan", "½", " "]),
        max_size=30).map(" ".join))
    def fuzz(text):
        check(text)

    fuzz()


def test_hostile_sql_over_http_is_a_400_never_a_500(seeded_db, tmp_path):
    from fastapi.testclient import TestClient

    from kb.service.http import create_app

    client = TestClient(create_app(seeded_db, token=""), raise_server_exceptions=False, base_url="http://127.0.0.1")
    before = _sha(seeded_db)
    for template in HOSTILE_SQL:
        response = client.post("/sql", json={"query": template.format(tmp=tmp_path), "timeout_s": 5})
        assert response.status_code == 400, (template, response.status_code, response.text)
        assert response.json()["error"] == "QueryRefused" and str(seeded_db.parent) not in response.text
    assert _sha(seeded_db) == before


_SQL_WORDS = st.sampled_from([
    "SELECT", "FROM", "objects", "UPDATE", "EXTENSIONS", "COPY", "TO", "'/tmp/x'", "ATTACH", "PRAGMA", "SET",
    "EXPLAIN", "ANALYZE", "WITH", "a", "AS", "(", ")", ";", ",", "*", "1", "range(10)", "INSTALL", "LOAD",
    "duckdb_databases()", "current_setting('x')", "'", '"', "--", "/*", "*/", "CALL", "VALUES", "DROP", "\x00",
])


@settings(max_examples=60, deadline=None, suppress_health_check=list(HealthCheck))
@given(words=st.lists(_SQL_WORDS, min_size=1, max_size=12))
def test_any_statement_is_answered_or_refused_never_a_crash(shared_seeded_db, words):
    kb = KnowledgeBase.open(shared_seeded_db, read_only=True)
    try:
        result = kb.sql(" ".join(words), timeout_s=5, max_rows=5)
    except (QueryRefused, QueryFailed) as err:
        assert str(err) and "\n" not in str(err)
        return
    assert len(result.rows) <= 5 and len(set(result.columns)) == len(result.columns)


@pytest.fixture(scope="module")
def shared_seeded_db(tmp_path_factory):
    from kb.service.bootstrap import seed_catalog_path

    db = tmp_path_factory.mktemp("fuzzsql") / "catalog.duckdb"
    KnowledgeBase.open(db).import_csv(seed_catalog_path())
    return db
