"""``objrecall catalog list`` on a narrow terminal: names break between words, never inside one."""

from __future__ import annotations

import pytest
from typer.testing import CliRunner

from kb.features import ObjectRecord
from kb.service.bootstrap import init_db
from kb.service.cli import app


@pytest.mark.parametrize("width", [72, 80])
def test_a_narrow_list_never_splits_a_word_of_a_name(tmp_path, monkeypatch, width):
    from rich.console import Console

    import kb.service.cli.catalog as catalog_cli

    monkeypatch.setattr(catalog_cli, "console", Console(width=width, color_system=None))
    db = tmp_path / "c.duckdb"
    kb = init_db(db, seed=True)
    # sizes with many digits and 'squeezable' widen the other columns, as an ingested catalog's do
    kb.upsert(
        [
            ObjectRecord(
                name="adjustable desk lamp",
                a_cm=123.45,
                b_cm=67.85,
                c_cm=12.35,
                mass_g=1234.5,
                shape="prism",
                material="metal",
                rigidity="squeezable",
            )
        ],
        source="test",
        adapter="test",
    )
    names = [o.name for o in kb.list_objects(limit=1000)]
    result = CliRunner().invoke(app, ["catalog", "list", "--db", str(db), "--limit", "1000"])
    assert result.exit_code == 0, result.output
    cells: set[str] = set()
    for line in result.output.splitlines():
        parts = line.split("│")
        if len(parts) > 2:
            cells.update(parts[1].split())
    words = {w for n in names for w in n.split() if len(w) <= 20}
    assert "adjustable" in words  # the word that was split ("adjustab" / "le") at 80 columns
    assert words <= cells, sorted(words - cells)[:10]
