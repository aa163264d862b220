"""scripts/real_pages.py's containers: a page stored inside a JavaScript template literal, a Python string or literal."""

import importlib.util
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

_SPEC = importlib.util.spec_from_file_location("real_pages", Path(__file__).parents[1] / "scripts" / "real_pages.py")
real_pages = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(real_pages)


def test_a_template_literal_is_cooked_as_javascript_does():
    source = "const a = `first`;\nconst $ = cheerio.load(`<p>l\\'utilisation \\`x\\` \\\\ \\$5</p>\\\n<b>`);"
    assert real_pages.js_template(source, 0) == "first"
    assert real_pages.js_template(source, 1) == "<p>l'utilisation `x` \\ $5</p><b>"


def test_a_template_literal_with_a_substitution_or_past_the_last_is_refused():
    with pytest.raises(SystemExit, match="substitution"):
        real_pages.js_template("x = `<p>${name}</p>`", 0)
    assert real_pages.js_template("x = `<p>\\${name}</p>`", 0) == "<p>${name}</p>"
    with pytest.raises(SystemExit, match="has 1"):
        real_pages.js_template("x = `<p></p>`", 1)


def test_a_python_string_is_the_one_assigned_to_the_name():
    source = 'OTHER = "<p>no</p>"\nPAGE = """<html>\\n<p>yes</p></html>"""\nPAGE_2 = "<p>no</p>"\n'
    assert real_pages.py_string(source, "PAGE") == "<html>\n<p>yes</p></html>"
    with pytest.raises(SystemExit, match="PAGE_3"):
        real_pages.py_string(source, "PAGE_3")


def test_unpack_reads_the_container_kind_and_member():
    js = "x = `<html>é</html>`;".encode()
    assert real_pages.unpack(js, "test.js", "jstemplate:0") == "<html>é</html>".encode()
    assert real_pages.unpack(b'P = "<html></html>"', "f.py", "pystr:P") == b"<html></html>"
    assert real_pages.unpack(b"{'url': 'u', 'html': '<html>\\n\\xe9</html>'}", "t.html", "pyliteral:html") \
        == "<html>\né</html>".encode()
    assert real_pages.unpack(b'{"pages": [{"html": "<p>1</p>"}]}', "t.json", "json:pages.0.html") == b"<p>1</p>"
    with pytest.raises(SystemExit, match="unknown container"):
        real_pages.unpack(b"", "f", "rar:x")


@given(st.text(alphabet=st.characters(blacklist_characters="`\\$", blacklist_categories=("Cs",))))
def test_text_without_escapes_comes_back_unchanged(text):
    assert real_pages.js_template(f"load(`{text}`)", 0) == text
    assert real_pages.py_string(f"PAGE = {text!r}", "PAGE") == text


def test_a_snapshot_with_a_work_tree_is_read_from_its_git_directory(tmp_path):
    bare = tmp_path / "owner+bare" / "repo"
    bare.mkdir(parents=True)
    inner = tmp_path / "owner+tree" / "repo" / ".git"
    inner.mkdir(parents=True)
    assert real_pages._git_dir(tmp_path, "owner/bare") == bare
    assert real_pages._git_dir(tmp_path, "owner/tree") == inner
    with pytest.raises(SystemExit, match="fetch it first"):
        real_pages._git_dir(tmp_path, "owner/absent")


def test_duplicates_names_each_later_copy_of_a_page(tmp_path):
    from types import SimpleNamespace

    files = {"a": b"<html>1</html>", "b": b"<html>2</html>", "c": b"<html>1</html>", "d": b"<html>1</html>"}
    pages = []
    for pid, body in files.items():
        (tmp_path / f"{pid}.html").write_bytes(body)
        pages.append(SimpleNamespace(id=pid, path=tmp_path / f"{pid}.html"))
    assert real_pages.duplicates(pages) == [("c", "a"), ("d", "a")]
    assert real_pages.duplicates(pages[:2]) == []


def test_no_page_of_the_corpus_is_there_twice():
    """A page captured by two repositories (a shared batch's page fetched again) is counted once."""
    from scrapers.corpus import load_corpus

    pages = load_corpus(labelled_only=False)
    if not pages:
        pytest.skip("no corpus page is present (cache and shared batches absent)")
    assert real_pages.duplicates(pages) == []


def test_a_page_store_comes_from_an_absolute_address_only():
    assert real_pages.page_store("https://www.101gigas.com/asus/rx580/") == "101gigas"
    assert real_pages.page_store("/asus/rx580/", store="101gigas") == "101gigas"
    with pytest.raises(SystemExit, match="not an absolute address"):
        real_pages.page_store("/asus/rx580/")  # a relative canonical link: its path is no store
    with pytest.raises(SystemExit, match="give --url or --store"):
        real_pages.page_store("")
