"""One writer at a time: real processes contend for one DuckDB file (see kb/catalog.py and the README)."""

import json
import subprocess
import sys
import textwrap
import time

import pytest

from kb.catalog import KnowledgeBase
from kb.errors import DatabaseBusy

HOLDER = textwrap.dedent(
    """
    import sys, time
    from kb.catalog import KnowledgeBase
    kb = KnowledgeBase.open(sys.argv[1], read_only=sys.argv[2] == "read")
    with kb.connect(write=sys.argv[2] == "write") as con:
        if sys.argv[2] == "write":
            con.begin()
            con.execute("insert into objects (name, a_cm) values ('held object', 3)")
        print("holding", flush=True)
        time.sleep(float(sys.argv[3]))
        if sys.argv[2] == "write":
            con.commit()
    print("released", flush=True)
    """
)


def hold(path, mode, seconds):
    proc = subprocess.Popen([sys.executable, "-c", HOLDER, str(path), mode, str(seconds)],
                            stdout=subprocess.PIPE, text=True)
    assert proc.stdout.readline().strip() == "holding"
    return proc


def test_reader_waits_for_writer_and_sees_its_commit(seeded_db):
    before = KnowledgeBase.open(seeded_db, read_only=True).count_objects()
    writer = hold(seeded_db, "write", 1.5)
    start = time.monotonic()
    count = KnowledgeBase.open(seeded_db, read_only=True, busy_timeout=20).count_objects()
    waited = time.monotonic() - start
    assert writer.wait(timeout=30) == 0
    assert count == before + 1  # it waited for the commit rather than failing
    assert waited > 0.2


def test_cli_reader_process_does_not_fail_while_writer_busy(seeded_db, cli_env):
    writer = hold(seeded_db, "write", 1.0)
    out = subprocess.run(["objrecall", "sql", "select count(*) as n from objects", "--db", str(seeded_db), "--json"],
                         capture_output=True, text=True, env=cli_env, timeout=60)
    assert writer.wait(timeout=30) == 0
    assert out.returncode == 0, out.stderr
    assert json.loads(out.stdout)["rows"][0]["n"] >= 101


def test_writer_waits_for_reader(seeded_db):
    reader = hold(seeded_db, "read", 1.0)
    kb = KnowledgeBase.open(seeded_db, busy_timeout=20)
    from kb.features import ObjectRecord

    kb.upsert([ObjectRecord.create("late writer", a_cm=1)], source="test", adapter="test")
    assert reader.wait(timeout=30) == 0
    assert kb.get_object("late writer").a_cm == 1


def test_busy_timeout_gives_clear_error(seeded_db):
    writer = hold(seeded_db, "write", 3.0)
    try:
        with pytest.raises(DatabaseBusy, match="another process has held the database"):
            KnowledgeBase.open(seeded_db, read_only=True, busy_timeout=0.3).count_objects()
    finally:
        writer.wait(timeout=30)
