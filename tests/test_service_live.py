"""The knowledge service over real HTTP: `objrecall serve` in a child process on a free 127.0.0.1 port.

The concurrency test runs a real `objrecall ingest` of the demo storefront (started through the API, so the
write endpoint is exercised too) and a second writer process holding long write transactions, while reader
threads keep querying: every read must succeed (reads may wait for a write; never a 5xx).
"""

from __future__ import annotations

import subprocess
import sys
import textwrap
import threading
import time
from pathlib import Path

import httpx
import pytest

from kb.service.http import serve_subprocess

pytestmark = pytest.mark.slow

TOKEN = "live-test-token"

SOURCES = """
[defaults]
delay_s = 0
read_timeout_s = 0.5
connect_timeout_s = 2
max_retries = 1
backoff_s = 0

[[stores]]
name = "demo"
base_url = "{base_url}"
sitemaps = ["{{base_url}}/sitemap.xml"]
"""

#: A second writer: three write transactions of about a second each through kb.upsert (the API a job uses).
LONG_WRITER = textwrap.dedent(
    """
    import sys, time
    from kb.catalog import KnowledgeBase
    from kb.features import ObjectRecord
    kb = KnowledgeBase.open(sys.argv[1])
    for i in range(3):
        with kb.connect(write=True) as con:
            con.begin()
            kb.upsert([ObjectRecord.create(f"slow writer object {i}", mass_g=10 + i, shape="compact")],
                      source="long-writer", adapter="test", con=con)
            print("holding", i, time.time(), flush=True)
            time.sleep(1.0)
            con.commit()
        time.sleep(0.3)
    print("done", flush=True)
    """
)


@pytest.fixture(scope="module")
def store():
    from scrapers.demo_store import DemoStore

    with DemoStore(crawl_delay=None, slow_s=0.5) as s:
        yield s


@pytest.fixture(scope="module")
def live(tmp_path_factory, store):
    """(base URL, catalog path) of a real server with writes enabled and a sources file for the demo store."""
    import os

    from kb.catalog import KnowledgeBase
    from kb.service.bootstrap import seed_catalog_path

    root = tmp_path_factory.mktemp("live")
    db = root / "catalog.duckdb"
    KnowledgeBase.open(db).import_csv(seed_catalog_path())
    sources = root / "sources.toml"
    sources.write_text(SOURCES.format(base_url=store.base_url))
    env = dict(os.environ)
    env["PATH"] = f"{Path(sys.executable).parent}{os.pathsep}{env.get('PATH', '')}"
    env["OBJRECALL_API_TOKEN"] = TOKEN
    env.pop("OBJRECALL_API_TOKEN_FILE", None)
    with serve_subprocess(
        db,
        env=env,
        extra_args=["--sources", str(sources), "--log-level", "warning", "--ingest-log-dir", str(root / "logs")],
    ) as base:
        yield base, db


def test_reads_over_http(live):
    base, _ = live
    with httpx.Client(base_url=base, timeout=60) as c:
        assert c.get("/health").json()["status"] == "ok"
        page = c.get("/objects", params={"limit": 5}).json()
        assert page["total"] > 100 and len(page["items"]) == 5
        assert c.get("/objects/tennis ball").json()["provenance"]
        top = c.post("/recall", json={"text": "a fuzzy yellow tennis ball, 58 g"}).json()["matches"][0]
        assert top["name"] == "tennis ball"
        assert c.get("/openapi.json").json()["info"]["title"] == "objrecall knowledge service"
        assert "<title>objrecall</title>" in c.get("/").text


@pytest.mark.parametrize(
    ("query", "status"),
    [
        ("SELECT * FROM read_csv('/etc/passwd')", 400),
        ("COPY objects TO '/tmp/objrecall-live-stolen.csv'", 400),
        ("ATTACH '/tmp/objrecall-live.duckdb' AS x", 400),
        ("INSTALL httpfs", 400),
        ("LOAD httpfs", 400),
    ],
)
def test_hostile_sql_over_http(live, query, status):
    base, _ = live
    r = httpx.post(f"{base}/sql", json={"query": query}, timeout=60)
    assert r.status_code == status, r.text
    assert r.json()["error"] == "QueryRefused"
    assert not Path("/tmp/objrecall-live-stolen.csv").exists()


def test_sql_limits_over_http(live):
    base, _ = live
    rows = httpx.post(
        f"{base}/sql",
        json={"query": "select * from range(CAST(10**9 AS BIGINT))", "max_rows": 50},
        timeout=60,
    )
    assert rows.status_code == 200 and len(rows.json()["rows"]) == 50 and rows.json()["truncated"]
    slow_query = "SELECT sum(hash(i)) FROM range(100000000000) t(i)"  # slow, in constant memory
    slow = httpx.post(f"{base}/sql", json={"query": slow_query, "timeout_s": 1}, timeout=60)
    assert slow.status_code == 504 and "time limit" in slow.json()["detail"]
    assert httpx.get(f"{base}/health", timeout=10).status_code == 200  # the server is fine afterwards


def test_writes_over_http_need_the_token(live):
    base, _ = live
    body = {"a_cm": 8, "b_cm": 8, "c_cm": 2, "mass_g": 90, "shape": "thin", "material": "wood"}
    assert httpx.put(f"{base}/objects/wooden coaster", json=body, timeout=60).status_code == 401
    r = httpx.put(
        f"{base}/objects/wooden coaster", json=body, headers={"Authorization": f"Bearer {TOKEN}"}, timeout=60
    )
    assert r.status_code == 201, r.text
    assert httpx.get(f"{base}/objects/wooden coaster", timeout=60).json()["mass_g"] == 90


def test_reads_keep_answering_while_the_nightly_job_writes(live):
    """A real ingestion (started through the API) and a long-transaction writer run while readers query."""
    base, db = live
    auth = {"Authorization": f"Bearer {TOKEN}"}
    before = httpx.get(f"{base}/objects", params={"limit": 1}, timeout=60).json()["total"]
    failures: list[str] = []
    counts = {"ok": 0}
    spans: list[tuple[float, float, str]] = []  # (start, end, path) of every successful read
    stop = threading.Event()

    def reader(kind: int) -> None:
        requests_ = [
            ("GET", "/objects", {"params": {"limit": 20, "offset": kind * 7}}),
            ("POST", "/recall", {"json": {"text": "a ceramic coffee mug about 10 cm tall, 330 g", "top": 3}}),
            # its time limit counts the wait for the writers: under load the default 5 s ran out (10 s: the most)
            ("POST", "/sql", {"json": {"query": "SELECT count(*) AS n FROM objects", "timeout_s": 10}}),
            ("GET", "/objects/coffee mug", {}),
            ("GET", "/ingestion/runs", {}),
        ]
        with httpx.Client(base_url=base, timeout=90) as c:
            i = kind
            while not stop.is_set():
                method, path, kw = requests_[i % len(requests_)]
                i += 1
                began = time.time()
                try:
                    r = c.request(method, path, **kw)
                except httpx.HTTPError as err:
                    failures.append(f"{method} {path}: {err!r}")
                    continue
                if r.status_code != 200:
                    failures.append(f"{method} {path}: {r.status_code} {r.text[:200]}")
                else:
                    counts["ok"] += 1
                    spans.append((began, time.time(), path))

    threads = [threading.Thread(target=reader, args=(k,), daemon=True) for k in range(4)]
    for t in threads:
        t.start()
    started = httpx.post(f"{base}/ingestion/runs", headers=auth, timeout=60)
    assert started.status_code == 202, started.text
    job = started.json()
    assert httpx.post(f"{base}/ingestion/runs", headers=auth, timeout=60).status_code == 409  # one at a time
    writer = subprocess.run(
        [sys.executable, "-c", LONG_WRITER, str(db)], capture_output=True, text=True, timeout=300
    )
    assert writer.returncode == 0, writer.stderr[-2000:]
    assert writer.stdout.count("holding") == 3
    holds = [float(line.split()[2]) for line in writer.stdout.splitlines() if line.startswith("holding")]
    deadline = time.monotonic() + 240
    while True:
        status = httpx.get(f"{base}{job['status_url']}", timeout=60).json()
        if status["status"] != "running" or time.monotonic() > deadline:
            break
        time.sleep(0.5)
    stop.set()
    for t in threads:
        t.join(timeout=120)
    assert status["status"] == "succeeded", status["log_tail"]
    assert failures == [], failures[:5]
    assert counts["ok"] >= 20
    # reads were in flight while the writer held the database, and succeeded (they waited, or recall
    # answered from its snapshot)
    during = [p for b, e, p in spans if any(b < h + 1.0 and e > h for h in holds)]
    assert during, (
        f"no read overlapped a write transaction: holds {holds}, spans {[(round(b, 2), round(e, 2), p) for b, e, p in spans][-40:]}"
    )
    runs = httpx.get(f"{base}/ingestion/runs", timeout=60).json()
    assert runs["runs"] and runs["runs"][0]["status"] == "ok"
    assert runs["jobs"][0]["id"] == job["id"]
    after = httpx.get(f"{base}/objects", params={"limit": 1}, timeout=60).json()["total"]
    assert after >= before + 3 + 10  # the writer's three objects and the storefront's new products
    assert httpx.get(f"{base}/objects/slow writer object 2", timeout=60).status_code == 200
