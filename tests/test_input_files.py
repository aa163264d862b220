"""Input files are read only when they are regular files, and only up to a cap: a device (``/dev/zero``) or a
named pipe never ends, and reading one grew the process until the kernel killed it (found by a blind test).
Each command refuses them in one line, at once, naming the file."""

from __future__ import annotations

import os

import pytest
from typer.testing import CliRunner

from kb.errors import CatalogImportError, DescriptionError, ExtractionError
from kb.files import read_input_file
from kb.service.cli import app

runner = CliRunner()


def test_a_file_of_exactly_the_cap_is_read_and_one_byte_more_is_refused(tmp_path):
    f = tmp_path / "f"
    f.write_bytes(b"x" * 10)
    assert read_input_file(f, 10) == b"x" * 10
    with pytest.raises(OSError, match="too large"):
        read_input_file(f, 9)


def test_a_directory_fails_as_a_directory(tmp_path):
    with pytest.raises(IsADirectoryError):
        read_input_file(tmp_path, 10)


@pytest.mark.skipif(not os.path.exists("/dev/zero"), reason="no /dev/zero")
def test_a_device_is_refused_before_reading():
    with pytest.raises(OSError, match="not a regular file"):
        read_input_file("/dev/zero", 10**12)


def test_a_named_pipe_is_refused_without_waiting_for_a_writer(tmp_path):
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)  # opening it would block until a writer comes: never opened
    with pytest.raises(OSError, match="not a regular file"):
        read_input_file(fifo, 10)


def test_a_symlink_to_a_regular_file_is_read(tmp_path):
    (tmp_path / "real").write_bytes(b"abc")
    (tmp_path / "link").symlink_to(tmp_path / "real")
    assert read_input_file(tmp_path / "link", 3) == b"abc"


@pytest.fixture
def fifo(tmp_path):
    path = tmp_path / "pipe.html"
    os.mkfifo(path)
    return str(path)


def test_every_reader_refuses_a_pipe_with_its_own_error(fifo):
    from kb.csvio import read_catalog_csv
    from recall.descriptions import read_description_column
    from scrapers.extract import extract_file

    with pytest.raises(ExtractionError, match="not a regular file"):
        extract_file(fifo)
    with pytest.raises(CatalogImportError, match="not a regular file"):
        read_catalog_csv(fifo)
    with pytest.raises(DescriptionError, match="not a regular file"):
        read_description_column(fifo)


@pytest.mark.parametrize(
    "args",
    [["extract", "{f}"], ["catalog", "import", "{f}", "--db", "{db}"], ["recall", "--file", "{f}", "--db", "{db}"],
     ["parse", "--file", "{f}"]],
    ids=lambda a: " ".join(a[:2]),
)
def test_the_cli_refuses_a_pipe_in_one_line(args, fifo, tmp_path):
    from kb.catalog import KnowledgeBase
    from kb.service.bootstrap import seed_catalog_path

    db = tmp_path / "c.duckdb"
    KnowledgeBase.open(db).import_csv(seed_catalog_path())
    result = runner.invoke(app, [a.format(f=fifo, db=db) for a in args])
    assert result.exit_code == 1, result.output
    lines = [ln for ln in result.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("Error: ") and "not a regular file" in lines[0], result.stderr
    assert fifo in lines[0]
