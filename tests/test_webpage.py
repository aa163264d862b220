"""The web page in headless Chromium against a real `objrecall serve` on 127.0.0.1: it lists the catalog,
shows the ranked matches of a description with their per-feature explanation and the chosen grasp, and a
catalog name holding HTML is shown as text (never run).

Chromium comes from Debian (`apt-get install chromium`, done by scripts/setup.sh); without it the tests are
skipped with that reason. The interactive test drives Chromium over the DevTools protocol with the
`websockets` package (skipped when it is absent).
"""

from __future__ import annotations

import contextlib
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import urllib.parse
from collections.abc import Iterator
from pathlib import Path

import httpx
import pytest

from kb.service.http import serve_subprocess

pytestmark = pytest.mark.slow

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
EVIL = '<script>document.title="pwned"</script><img src=x onerror="document.title=1"> gadget'
EVIL_NAME = EVIL.lower()  # names are stored lower-cased

needs_chromium = pytest.mark.skipif(
    CHROMIUM is None, reason="chromium not installed (apt-get install chromium)"
)

CHROMIUM_FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--disable-dev-shm-usage",
    "--mute-audio",
]


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    """A served catalog: the seed objects plus one whose name is HTML (as a scraped page could give)."""
    from kb.catalog import KnowledgeBase
    from kb.features import ObjectRecord
    from kb.service.bootstrap import seed_catalog_path

    db = tmp_path_factory.mktemp("web") / "catalog.duckdb"
    kb = KnowledgeBase.open(db)
    kb.import_csv(seed_catalog_path())
    evil = ObjectRecord.create(EVIL, a_cm=3, b_cm=2, c_cm=1, mass_g=12, shape="compact", material="plastic")
    kb.upsert([evil], source="a scraped page", adapter="test")
    env = dict(os.environ)
    env["PATH"] = f"{Path(sys.executable).parent}{os.pathsep}{env.get('PATH', '')}"
    env.pop("OBJRECALL_API_TOKEN", None)
    env.pop("OBJRECALL_API_TOKEN_FILE", None)
    with serve_subprocess(db, env=env, extra_args=["--log-level", "warning"]) as base:
        httpx.post(f"{base}/recall", json={"text": "warm up: a mug"}, timeout=120)  # build the parser first
        yield base


def _stop_browser(proc: subprocess.Popen, grace: float = 10.0) -> None:
    """Stop Chromium and every helper process it forked (they share its session and go on writing
    into the profile directory after the browser itself exits, which made the profile's removal fail).
    """
    for sig in (signal.SIGTERM, signal.SIGKILL):
        with contextlib.suppress(ProcessLookupError):
            os.killpg(proc.pid, sig)
        with contextlib.suppress(subprocess.TimeoutExpired):
            proc.wait(timeout=grace)
        deadline = time.monotonic() + grace
        while time.monotonic() < deadline and _group_alive(proc.pid):
            time.sleep(0.1)
        if not _group_alive(proc.pid):
            return


def _group_alive(pgid: int) -> bool:
    """Whether any process of the group still runs (zombies waiting for a reaper do not count)."""
    for status in Path("/proc").glob("[0-9]*/stat"):
        with contextlib.suppress(OSError):
            fields = status.read_text().rsplit(")", 1)[1].split()
            if int(fields[2]) == pgid and fields[0] != "Z":  # fields: state, ppid, pgrp
                return True
    return False


@contextlib.contextmanager
def _profile_dir(prefix: str) -> Iterator[str]:
    # a crashed helper may leave a lock file behind; the directory is scratch either way
    with tempfile.TemporaryDirectory(prefix=prefix, ignore_cleanup_errors=True) as profile:
        yield profile


def dump_dom(url: str) -> str:
    """The page's DOM after its scripts ran (virtual time lets the fetches finish first)."""
    with _profile_dir("objrecall-chromium-") as profile:
        proc = subprocess.Popen(
            [CHROMIUM, *CHROMIUM_FLAGS, f"--user-data-dir={profile}", "--virtual-time-budget=20000",
             "--dump-dom", url],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True,
        )  # fmt: skip
        try:
            out, err = proc.communicate(timeout=180)
        finally:
            _stop_browser(proc)
    assert proc.returncode == 0, err[-2000:]
    return out


@needs_chromium
def test_page_lists_the_catalog_and_recalls_from_the_url(site):
    q = urllib.parse.quote("a fuzzy yellow tennis ball, about 6.5 cm across, 58 g")
    dom = dump_dom(f"{site}/?q={q}")
    assert 'data-ready="true"' in dom, dom[-3000:]
    # the catalog table: a page of rows, with the total
    catalog = dom[dom.index('id="catalog"') :]
    assert len(re.findall(r"<tr data-name=", catalog)) == 25
    assert re.search(r"1-25 of \d{3} objects", dom)
    # the recall: the expected top match, ranked rows with per-feature contributions, the grasp
    assert re.search(r'id="top-match">tennis ball<', dom)
    matches = dom[dom.index('id="matches"') : dom.index('id="catalog"')]
    assert matches.index('data-name="tennis ball"') < matches.index("</tbody>")
    assert 'data-feature="mass_g"' in matches
    assert re.search(r'id="grasp-type" data-grasp="[a-z_]+"', dom)
    assert "confidence" in dom
    # its simulated grasp: not validated in this fresh catalog yet, said so, with the render of the plan
    assert re.search(r'id="grasp-validation">Not validated in simulation', dom)
    assert re.search(r'<img id="grasp-render" alt="tennis ball: [a-z_]+ \(simulated\)" src="/grasp/render\?object=tennis%20ball&amp;grasp_type=[a-z_]+"', dom)


@needs_chromium
def test_page_says_not_in_the_catalog_and_plans_for_the_described_object(site):
    q = urllib.parse.quote("An orange of 7 cm diameter.")
    dom = dump_dom(f"{site}/?q={q}")
    assert 'data-ready="true"' in dom, dom[-3000:]
    assert re.search(r'id="not-in-catalog">Not in the catalog<', dom)
    assert "no 'orange' (kind: fruit)" in dom and "closest fruit: apple" in dom
    assert re.search(r"confidence 0\.0[0-5]", dom)  # the CLI's line, NOT_IN_CATALOG_CONFIDENCE at most
    assert "planned for the described orange: not in the catalog" in dom


@needs_chromium
def test_html_in_a_catalog_name_is_shown_as_text(site):
    dom = dump_dom(f"{site}/")
    assert 'data-ready="true"' in dom
    assert dom.count("<script") == 1, "only the page's own script element"  # app.js
    assert "<img" not in dom
    assert "&lt;script&gt;document.title=" in dom  # the name, escaped, as text in the table
    assert "<title>objrecall</title>" in dom  # neither payload ran


def _cdp_browser(profile: str) -> tuple[subprocess.Popen, str]:
    proc = subprocess.Popen(
        [CHROMIUM, *CHROMIUM_FLAGS, f"--user-data-dir={profile}", "--remote-debugging-port=0",
         "--remote-allow-origins=*", "about:blank"],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True,
    )  # fmt: skip
    port_file = Path(profile) / "DevToolsActivePort"
    deadline = time.monotonic() + 60
    while not port_file.exists() or not port_file.read_text().strip():
        if time.monotonic() > deadline or proc.poll() is not None:
            _stop_browser(proc)
            pytest.fail("chromium did not open its DevTools port")
        time.sleep(0.1)
    port = int(port_file.read_text().split()[0])
    pages = httpx.get(f"http://127.0.0.1:{port}/json/list", timeout=10).json()
    return proc, next(p["webSocketDebuggerUrl"] for p in pages if p["type"] == "page")


class DevTools:
    """The least of the Chrome DevTools protocol: send a command, wait for its answer."""

    def __init__(self, ws):
        self.ws = ws
        self.next_id = 0

    def call(self, method: str, **params):
        self.next_id += 1
        self.ws.send(json.dumps({"id": self.next_id, "method": method, "params": params}))
        while True:
            message = json.loads(self.ws.recv(timeout=60))
            if message.get("id") == self.next_id:
                if "error" in message:
                    raise AssertionError(f"{method}: {message['error']}")
                return message["result"]

    def eval(self, expression: str):
        result = self.call("Runtime.evaluate", expression=expression, returnByValue=True, awaitPromise=True)
        if "exceptionDetails" in result:
            raise AssertionError(f"{expression}: {result['exceptionDetails']}")
        return result["result"].get("value")

    def wait_for(self, expression: str, timeout: float = 90.0):
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            value = self.eval(expression)
            if value:
                return value
            time.sleep(0.2)
        raise AssertionError(f"timed out waiting for {expression}")


@contextlib.contextmanager
def browser_at(url: str) -> Iterator[DevTools]:
    """Headless Chromium on ``url``, driven over the DevTools protocol, once the page says it is ready."""
    sync_client = pytest.importorskip(
        "websockets.sync.client", reason="the websockets package drives Chromium"
    )
    with _profile_dir("objrecall-cdp-") as profile:
        proc, ws_url = _cdp_browser(profile)
        try:
            with sync_client.connect(ws_url, max_size=None) as ws:
                tools = DevTools(ws)
                tools.call("Page.enable")
                tools.call("Page.navigate", url=url)
                tools.wait_for("document.body && document.body.dataset.ready === 'true'")
                yield tools
        finally:
            _stop_browser(proc)


@needs_chromium
def test_typing_a_description_shows_matches_and_paging_works(site):
    with browser_at(f"{site}/") as tools:
        names = tools.eval(
            "[...document.querySelectorAll('#catalog tbody tr')].map(r => r.dataset.name)"
        )
        assert EVIL_NAME in names  # '<' sorts early: the HTML name is on the first page, as text
        cell = f"[...document.querySelectorAll('#catalog td.name')].find(td => td.textContent === {json.dumps(EVIL_NAME)})"
        assert tools.eval(f"{cell}.childElementCount") == 0  # text only, no elements parsed from it
        first = names[0]
        tools.eval("document.getElementById('next').click()")
        tools.wait_for("document.getElementById('page-info').textContent.startsWith('26-')")
        assert tools.eval("document.querySelector('#catalog tbody tr').dataset.name") != first
        tools.eval(
            "document.getElementById('q').value = 'a metal frying pan with a long handle, 48 cm long, 1.2 kg';"
            "document.getElementById('recall-button').click()"
        )
        top = tools.wait_for("(document.getElementById('top-match') || {}).textContent")
        assert top == "frying pan"
        rows = tools.eval("document.querySelectorAll('#matches tbody tr').length")
        assert rows == 5
        explained = tools.eval(
            "[...document.querySelectorAll('#matches .contrib')].map(e => e.dataset.feature)"
        )
        assert "mass_g" in explained
        grasp = tools.wait_for(
            "(document.getElementById('grasp-type') || {dataset: {}}).dataset.grasp"
        )
        assert grasp
        # the render of the grasp arrives from the server (a real MuJoCo image) and is shown
        width = tools.wait_for(
            "(document.getElementById('grasp-render') || {}).complete && "
            "document.getElementById('grasp-render').naturalWidth"
        )
        assert width == 480
        assert tools.eval("new URL(location.href).searchParams.get('q')").startswith(
            "a metal frying pan"
        )
        assert tools.eval("document.title") == "objrecall"
