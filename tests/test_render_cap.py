"""The cost cap of ``GET /grasp/render`` (kb/service/http/renders.py): at most N renders at once (more get
503 with Retry-After), renders cached by object, features, grasp type, planner and hand."""

from __future__ import annotations

import threading
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from kb.errors import RenderBusy
from kb.service.http import create_app
from kb.service.http.renders import RenderCache

LOCAL = {"raise_server_exceptions": False, "base_url": "http://127.0.0.1"}


def test_a_render_is_made_once_then_served_from_the_cache():
    cache = RenderCache(max_concurrent=1, max_entries=4)
    made = []
    render = lambda: made.append(1) or b"png"  # noqa: E731
    assert cache.get_or_render("k", render) == (b"png", False)
    assert cache.get_or_render("k", render) == (b"png", True)
    assert len(made) == 1 and (cache.hits, cache.misses) == (1, 1)


def test_the_cache_keeps_exactly_max_entries_least_recently_used_out():
    cache = RenderCache(max_concurrent=1, max_entries=2)
    for key in ("a", "b"):
        cache.get_or_render(key, lambda key=key: key.encode())
    cache.get_or_render("a", lambda: b"again")  # a hit: "a" is now the most recent
    cache.get_or_render("c", lambda: b"c")  # a third entry: "b" goes
    assert len(cache) == 2
    assert cache.get_or_render("a", lambda: b"new")[1] is True
    assert cache.get_or_render("b", lambda: b"b2") == (b"b2", False)


def test_no_cache_when_max_entries_is_zero():
    cache = RenderCache(max_concurrent=1, max_entries=0)
    cache.get_or_render("k", lambda: b"1")
    assert cache.get_or_render("k", lambda: b"2") == (b"2", False) and len(cache) == 0


def _hold_renders(cache: RenderCache, n: int):
    """Start ``n`` renders that block until the returned event is set; returns (event, threads)."""
    release, started = threading.Event(), threading.Semaphore(0)

    def slow() -> bytes:
        started.release()
        release.wait(10)
        return b"slow"

    threads = [threading.Thread(target=cache.get_or_render, args=(f"slow{i}", slow)) for i in range(n)]
    for t in threads:
        t.start()
    for _ in range(n):
        assert started.acquire(timeout=10)
    return release, threads


@pytest.mark.parametrize("limit", [1, 2])
def test_exactly_max_concurrent_renders_run_and_the_next_is_refused_with_a_retry_time(limit):
    cache = RenderCache(max_concurrent=limit, max_entries=8, retry_after_s=3)
    release, threads = _hold_renders(cache, limit)  # exactly the limit runs at once
    try:
        with pytest.raises(RenderBusy, match=f"{limit} grasp renders are running") as err:
            cache.get_or_render("another", lambda: b"x")
        assert err.value.retry_after_s == 3
    finally:
        release.set()
        for t in threads:
            t.join(10)
    assert cache.get_or_render("another", lambda: b"x") == (b"x", False)  # a slot is free again
    assert cache.get_or_render("slow0", lambda: b"y") == (b"slow", True)  # cache hits need no slot


def test_a_failed_render_frees_its_slot_and_is_not_cached():
    cache = RenderCache(max_concurrent=1, max_entries=4)

    def broken() -> bytes:
        raise RuntimeError("no OpenGL")

    with pytest.raises(RuntimeError):
        cache.get_or_render("k", broken)
    assert cache.get_or_render("k", lambda: b"ok") == (b"ok", False)


def test_absurd_limits_are_refused():
    with pytest.raises(ValueError, match="max_concurrent"):
        RenderCache(max_concurrent=0)


@pytest.fixture(scope="module")
def render_client(tmp_path_factory) -> TestClient:
    from kb.catalog import KnowledgeBase
    from kb.service.bootstrap import seed_catalog_path

    path: Path = tmp_path_factory.mktemp("render") / "catalog.duckdb"
    KnowledgeBase.open(path).import_csv(seed_catalog_path())
    return TestClient(create_app(path, token=""), **LOCAL)


def test_the_route_caches_its_real_render_and_says_so(render_client):
    params = {"object": "coffee mug", "grasp_type": "heavy_wrap_large_diameter"}
    first = render_client.get("/grasp/render", params=params)
    assert first.status_code == 200, first.text
    assert first.headers["content-type"] == "image/png" and first.content[:8] == b"\x89PNG\r\n\x1a\n"
    assert first.headers["x-render-cache"] == "miss"
    again = render_client.get("/grasp/render", params={**params, "object": "mug"})  # an alias: same object
    assert again.headers["x-render-cache"] == "hit" and again.content == first.content


def test_the_route_answers_503_with_retry_after_when_every_slot_is_taken(render_client):
    cache = render_client.app.state.service.renders
    release, threads = _hold_renders(cache, cache.max_concurrent)
    try:
        r = render_client.get("/grasp/render", params={"object": "tennis ball", "grasp_type": "power_sphere"})
    finally:
        release.set()
        for t in threads:
            t.join(10)
    assert r.status_code == 503, r.text
    assert r.headers["retry-after"] == str(cache.retry_after_s)
    assert r.json()["error"] == "RenderBusy" and "retry in" in r.json()["detail"]
