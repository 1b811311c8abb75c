"""The version has one source (pyproject.toml) and every way to ask for it prints it."""

import subprocess
import sys
import tomllib
from importlib.metadata import version
from pathlib import Path

import tendonsheath as ts

ROOT = Path(__file__).resolve().parents[1]


def _pyproject_version() -> str:
    return tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["version"]


def test_package_version_is_the_metadata_and_pyproject_version():
    assert ts.__version__ == version("tendonsheath") == _pyproject_version()


def _printed(command: list[str]) -> str:
    done = subprocess.run(command, capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert done.stderr == ""
    return done.stdout


def test_cli_version_prints_the_metadata_version():
    exe = Path(sys.executable).with_name("tendonsheath")
    assert _printed([str(exe), "--version"]) == f"tendonsheath {version('tendonsheath')}\n"


def test_python_m_version_prints_the_metadata_version():
    out = _printed([sys.executable, "-m", "tendonsheath", "--version"])
    assert out == f"tendonsheath {version('tendonsheath')}\n"


def test_python_m_runs_the_same_command_as_the_script():
    out = _printed([sys.executable, "-m", "tendonsheath", "--help"])
    for command in ("demo", "identify", "compare", "sweep", "bench"):
        assert command in out
    assert "--version" in out
