"""Shared fixtures: the repository root and the built `stiction` binary the results are compared with."""

import json
import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[3]


def _binary() -> pathlib.Path:
    env = os.environ.get("STICTION_BIN")
    if env:
        return pathlib.Path(env)
    target = pathlib.Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    path = target / "release" / "stiction"
    if not path.exists():
        subprocess.run(["cargo", "build", "--release", "-q", "-p", "stiction-cli"], cwd=ROOT, check=True)
    return path


@pytest.fixture(scope="session")
def cli():
    """cli(*args) -> (exit status, stdout, stderr) of the `stiction` binary run in the repository root."""
    binary = _binary()

    def call(*args):
        p = subprocess.run([str(binary), *map(str, args)], cwd=ROOT, capture_output=True, text=True)
        return p.returncode, p.stdout, p.stderr

    return call


@pytest.fixture(scope="session")
def cli_json(cli):
    """cli_json(*args) -> json.loads of `stiction ARGS --json` (which must succeed)."""

    def call(*args):
        code, out, err = cli(*args, "--json")
        assert code == 0, err
        return json.loads(out)

    return call


@pytest.fixture
def in_root(monkeypatch):
    """Run the test in the repository root, so that relative scenario paths name the same files."""
    monkeypatch.chdir(ROOT)
    return ROOT


def python_names(message: str, names) -> str:
    """A command-line message with each flag that is one of the Python arguments `names` written
    as that argument (`--e-star` -> `e_star`, clap's `'--grid <GRID>'` -> `'grid'`): the binding's
    rule for the messages of arguments it turns into flags (errors name what the caller typed)."""
    import re

    def name(m):
        arg = m[1].replace("-", "_")
        return arg if arg in names else m[0]

    return re.sub(r"(?<![\w-])--([a-z][a-z0-9-]*)(?: <[A-Z_:|]+>)?", name, message)
