#!/usr/bin/env python3
"""Build and check the real-page corpus cache from fetched repository snapshots.

    python scripts/real_pages.py materialize [--mirror /work/.mirror] [--cache DIR]
    python scripts/real_pages.py check [--cache DIR]
    python scripts/real_pages.py add REPO PATH [--member M] [--url U] [--language L] [--by NAME] [--shard NAME]

``materialize`` copies every page of ``tests/data/real_pages/manifest*.jsonl`` out of its snapshot
(``<mirror>/<owner>+<name>/repo``, a bare git directory that the search tool's ``fetch`` brings) at the
manifest's commit, unpacks it (``container``: gzip, ``json:<key>`` for a page stored inside a JSON
document, ``zip:<member>``, ``tar:<member>``, ``jstemplate:<n>`` for the n-th backtick template literal
of a JavaScript file, ``pystr:<name>`` for a string a Python module assigns to ``name``, ``pyliteral:<key>`` for
a page inside a file that is one Python literal, such as a dict's repr), checks its sha256 and writes ``<cache>/<id>.html``.
Nothing fetched is committed: only the manifest and the labels are.

``add`` appends one page to a manifest shard (``manifest-<shard>.jsonl``): it reads the page from the
snapshot's newest commit, records the commit and sha256, and prints the new id. The store is derived
from ``--url`` (``scrapers.corpus.store_group``); give ``--store`` when the page has no address.
"""

from __future__ import annotations

import argparse
import ast
import gzip
import hashlib
import io
import json
import re
import subprocess
import sys
import tarfile
import zipfile
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from scrapers.corpus import CORPUS_DIR, cache_dir, held_out, load_corpus, load_manifest, store_group  # noqa: E402

MIRROR = Path("/work/.mirror")


def _git_dir(mirror: Path, repo: str) -> Path:
    path = mirror / repo.replace("/", "+") / "repo"
    if (path / ".git").is_dir():  # a snapshot fetched with a work tree keeps its git directory inside
        path = path / ".git"
    if not path.is_dir():
        raise SystemExit(f"no snapshot of {repo} at {path}: fetch it first (search tool: fetch github:{repo})")
    return path


def _blob(git_dir: Path, commit: str, path: str) -> bytes:
    out = subprocess.run(["git", "--git-dir", str(git_dir), "show", f"{commit}:{path}"], capture_output=True)
    if out.returncode:
        raise SystemExit(f"{path} at {commit[:10]}: {out.stderr.decode(errors='replace').strip()}")
    return out.stdout


def _head(git_dir: Path) -> str:
    return subprocess.run(["git", "--git-dir", str(git_dir), "rev-parse", "HEAD"], capture_output=True,
                          text=True, check=True).stdout.strip()


_JS_ESCAPES = {"n": "\n", "t": "\t", "r": "\r", "\n": ""}  # a backslash-newline continues the line


def js_template(source: str, index: int) -> str:
    """The ``index``-th backtick template literal of a JavaScript ``source``, cooked as JavaScript does.

    A literal with a ``${...}`` substitution is refused: its text is not the stored page.
    """
    literals = re.findall(r"`((?:[^`\\]|\\.)*)`", source, flags=re.S)
    if index >= len(literals):
        raise SystemExit(f"no template literal {index}: the file has {len(literals)}")
    raw = literals[index]
    if re.search(r"(?<!\\)\$\{", raw):
        raise SystemExit(f"template literal {index} has a ${{...}} substitution")
    return re.sub(r"\\(.)", lambda m: _JS_ESCAPES.get(m.group(1), m.group(1)), raw, flags=re.S)


def py_string(source: str, name: str) -> str:
    """The string literal a Python module's top level assigns to ``name``."""
    for node in ast.parse(source).body:
        if isinstance(node, ast.Assign) and isinstance(node.value, ast.Constant) \
                and isinstance(node.value.value, str) \
                and any(isinstance(t, ast.Name) and t.id == name for t in node.targets):
            return node.value.value
    raise SystemExit(f"no string assigned to {name!r}")


def member_of(value, key_path: str):
    """The value at a dotted ``key_path`` (``a.b.0``) of a parsed JSON document or Python literal."""
    for key in key_path.split("."):
        value = value[int(key)] if isinstance(value, (list, tuple)) else value[key]
    return value


def unpack(data: bytes, path: str, container: str | None) -> bytes:
    """The page's own bytes from the stored file (see the module doc for ``container``)."""
    if container is None and path.endswith(".gz"):
        container = "gzip"
    if not container:
        return data
    kind, _, member = container.partition(":")
    if kind == "gzip":
        return gzip.decompress(data)
    if kind in ("json", "pyliteral"):
        value = json.loads(data) if kind == "json" else ast.literal_eval(data.decode("utf-8"))
        value = member_of(value, member)
        return value.encode("utf-8") if isinstance(value, str) else bytes(value)
    if kind == "zip":
        with zipfile.ZipFile(io.BytesIO(data)) as archive:
            return archive.read(member)
    if kind == "tar":
        with tarfile.open(fileobj=io.BytesIO(data)) as archive:
            return archive.extractfile(member).read()
    if kind == "jstemplate":
        return js_template(data.decode("utf-8"), int(member)).encode("utf-8")
    if kind == "pystr":
        return py_string(data.decode("utf-8"), member).encode("utf-8")
    raise SystemExit(f"unknown container {container!r}")


def materialize(mirror: Path, cache: Path) -> int:
    cache.mkdir(parents=True, exist_ok=True)
    done = missing = 0
    for row in load_manifest():
        target = cache / f"{row['id']}.html"
        if target.is_file() and hashlib.sha256(target.read_bytes()).hexdigest() == row["sha256"]:
            done += 1
            continue
        try:
            git_dir = _git_dir(mirror, row["source_repo"])
        except SystemExit as e:
            print(f"skip {row['id']}: {e}", file=sys.stderr)
            missing += 1
            continue
        page = unpack(_blob(git_dir, row["commit"], row["path"]), row["path"], row.get("container"))
        digest = hashlib.sha256(page).hexdigest()
        if digest != row["sha256"]:
            raise SystemExit(f"{row['id']}: sha256 {digest[:12]} is not the manifest's {row['sha256'][:12]}")
        target.write_bytes(page)
        done += 1
    print(f"{done} pages in {cache}; {missing} whose snapshot is missing")
    return 1 if missing else 0


def add(args) -> int:
    git_dir = _git_dir(args.mirror, args.repo)
    commit = args.commit or _head(git_dir)
    container = f"{args.container}:{args.member}" if args.member else args.container
    page = unpack(_blob(git_dir, commit, args.path), args.path, container)
    digest = hashlib.sha256(page).hexdigest()
    store = page_store(args.url, args.store)
    known = known_pages(args.cache or cache_dir())
    if digest in known:
        raise SystemExit(f"already in the corpus as {known[digest]}")
    pid = f"{store}-{digest[:10]}"
    row = {"id": pid, "source_repo": args.repo, "path": args.path, "commit": commit, "container": container,
           "sha256": digest, "bytes": len(page), "url": args.url, "store": store, "language": args.language,
           "licence": args.licence, "collected_by": args.by}
    with (CORPUS_DIR / f"manifest-{args.shard}.jsonl").open("a", encoding="utf-8") as out:
        out.write(json.dumps(row, ensure_ascii=False) + "\n")
    cache = args.cache or cache_dir()
    cache.mkdir(parents=True, exist_ok=True)
    (cache / f"{pid}.html").write_bytes(page)
    print(pid)
    return 0


def page_store(url: str, store: str = "") -> str:
    """The split key of a page: ``store`` when given, else the store of ``url``, which must be absolute
    (a relative address such as ``/brand/item/`` has no host, and its path is no store)."""
    if store:
        return store
    if not url:
        raise SystemExit("give --url or --store: the store is what the split is by")
    if not re.match(r"[a-z][a-z0-9+.-]*://[^/\s]+", url, flags=re.I):
        raise SystemExit(f"--url {url!r} is not an absolute address: give the page's full address or --store")
    return store_group(url)


def known_pages(cache: Path) -> dict[str, str]:
    """sha256 -> id of every page the corpus has: the manifests' rows and the shared batches' pages (a
    page captured by two public repositories is one page, whichever batch it came in)."""
    known = {row["sha256"]: row["id"] for row in load_manifest()}
    for page in load_corpus(cache=cache, shared=True, labelled_only=False):
        if page.source.get("sha256") is None:  # a shared batch's page: no manifest row
            known.setdefault(hashlib.sha256(page.path.read_bytes()).hexdigest(), page.id)
    return known


def duplicates(pages) -> list[tuple[str, str]]:
    """Pairs of present pages with the same bytes (the later one, the first one)."""
    seen: dict[str, str] = {}
    out = []
    for page in pages:
        digest = hashlib.sha256(page.path.read_bytes()).hexdigest()
        if digest in seen:
            out.append((page.id, seen[digest]))
        seen.setdefault(digest, page.id)
    return out


def check(cache: Path) -> int:
    rows = load_manifest()
    pages = load_corpus(cache=cache, shared=True, labelled_only=False)
    twins = duplicates(pages)
    for later, first in twins:
        print(f"{later}: the same page as {first}")
    labelled = [p for p in pages if p.truth is not None]
    stores = Counter(p.store for p in pages)
    langs = Counter(p.language for p in pages)
    print(f"manifest rows {len(rows)}; present (with shared batches) {len(pages)}; labelled {len(labelled)}")
    print(f"stores {len(stores)} ({sum(held_out(s) for s in stores)} held out); languages {len(langs)}: "
          + ", ".join(f"{k or '?'} {v}" for k, v in langs.most_common()))
    held = [p for p in labelled if p.held_out]
    print(f"labelled pages: development {len(labelled) - len(held)}, held out {len(held)}")
    return 1 if twins else 0


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mirror", type=Path, default=MIRROR)
    parser.add_argument("--cache", type=Path, default=None)
    sub = parser.add_subparsers(dest="command", required=True)
    sub.add_parser("materialize")
    sub.add_parser("check")
    a = sub.add_parser("add")
    a.add_argument("repo")
    a.add_argument("path")
    a.add_argument("--commit")
    a.add_argument("--container", help="gzip, json, zip, tar, jstemplate, pystr or pyliteral (with --member)")
    a.add_argument("--member", help="json or pyliteral key path (a.b.0), zip or tar member, template literal index, Python name")
    a.add_argument("--url", default="")
    a.add_argument("--store", default="")
    a.add_argument("--language", default="")
    a.add_argument("--licence", default="")
    a.add_argument("--by", default="")
    a.add_argument("--shard", default="main")
    args = parser.parse_args(argv)
    if args.command == "materialize":
        return materialize(args.mirror, args.cache or cache_dir())
    if args.command == "check":
        return check(args.cache or cache_dir())
    return add(args)


if __name__ == "__main__":
    raise SystemExit(main())
