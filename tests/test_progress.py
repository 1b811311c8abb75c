"""Progress on long work: a bar on a terminal, nothing under --quiet or off a terminal."""

import io
import sys

import pytest
import typer
from typer.testing import CliRunner

from tendonsheath._util import progress as _progress
from tendonsheath._util.progress import StepProgress, wanted
from tendonsheath.apps.cli import app

LONG_COMMANDS = ("identify", "compare", "sweep", "bench", "demo")


class _Terminal(io.StringIO):
    def isatty(self):
        return True


def _run_bar(enabled, **kwargs):
    with StepProgress(enabled, 3, "starting", "runs", transient=False, **kwargs) as bar:
        for name in ("calibration", "tracking", "honesty panel"):
            bar.step(name)


@pytest.mark.parametrize("command", LONG_COMMANDS)
def test_every_long_command_accepts_quiet(command):
    group = typer.main.get_command(app)
    sub = group.get_command(group.context_class(group), command)  # typer's own click
    flags = {opt for p in sub.params for opt in getattr(p, "opts", [])}
    assert {"--quiet", "-q"} <= flags, flags


def test_bar_on_a_terminal_counts_the_steps(monkeypatch):
    terminal = _Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    assert wanted(quiet=False) and not wanted(quiet=True)
    _run_bar(True)
    text = terminal.getvalue()
    assert "3/3" in text and "runs" in text and "honesty panel" in text


def test_no_bar_when_quiet_even_on_a_terminal(monkeypatch):
    terminal = _Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    _run_bar(wanted(quiet=True))
    assert terminal.getvalue() == ""


def test_no_bar_off_a_terminal(monkeypatch):
    pipe = io.StringIO()
    monkeypatch.setattr(sys, "stderr", pipe)
    assert not _progress.wanted(quiet=False)
    _run_bar(True)  # enabled, but stderr is not a terminal
    assert pipe.getvalue() == ""


def test_sweep_command_prints_no_bar_off_a_terminal(tmp_path):
    from test_cli_sweep import TOML

    cfg = tmp_path / "sweep.toml"
    cfg.write_text(TOML.replace("n = 6", "n = 2").replace("workers = 2", "workers = 1"))
    for extra in ([], ["--quiet"]):
        result = CliRunner().invoke(
            app, ["sweep", str(cfg), "--out", str(tmp_path / "o"), "--no-figures", *extra]
        )
        assert result.exit_code == 0, result.output
        assert "ETA" not in result.output and "runs" not in result.output.split("mse over")[0]


def test_identify_search_uses_the_shared_bar(monkeypatch):
    import importlib

    search = importlib.import_module("tendonsheath.identify.search")
    terminal = _Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    bar = search._Progress(True, "Backlash", 10)
    bar.start -= 2.0  # past the second a bar waits for
    for generation in range(1, 11):
        bar.update(generation, 1.0 / generation)
    bar.close()
    text = terminal.getvalue()
    assert "10/10" in text and "generations" in text and "best cost 0.1" in text
    quiet = search._Progress(False, "Backlash", 10)
    quiet.start -= 2.0
    quiet.update(1, 1.0)
    assert quiet.bar is None
