"""The progress display of compare_models: one bar over every candidate's fits, with an ETA."""

from __future__ import annotations

import sys


class CompareProgress:
    """A rich bar counting the fits (candidates x folds, and the winner's final fit), naming
    the current candidate and fold, with the elapsed time and an ETA. Silent unless
    ``enabled`` and the output is a terminal."""

    def __init__(self, enabled: bool, total: int):
        self.bar = None
        if not enabled or not sys.stderr.isatty():
            return
        from rich.console import Console
        from rich.progress import (
            BarColumn,
            MofNCompleteColumn,
            Progress,
            TextColumn,
            TimeElapsedColumn,
            TimeRemainingColumn,
        )

        self.bar = Progress(
            TextColumn("{task.description}"),
            BarColumn(),
            MofNCompleteColumn(),
            TextColumn("fits"),
            TimeElapsedColumn(),
            TextColumn("ETA"),
            TimeRemainingColumn(),
            console=Console(stderr=True),
            transient=True,
        )
        self.bar.start()
        self.task = self.bar.add_task("comparing", total=total)

    def show(self, what: str) -> None:
        if self.bar is not None:
            self.bar.update(self.task, description=what)

    def advance(self) -> None:
        if self.bar is not None:
            self.bar.advance(self.task)

    def print(self, line: str) -> None:
        """A line above the bar (or on stdout without one)."""
        if self.bar is not None:
            self.bar.console.print(line, highlight=False)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.stop()
            self.bar = None
