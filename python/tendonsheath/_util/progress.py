"""The one progress display of the long commands (identify's comparison, compare, sweep, bench,
demo): a rich bar on stderr with the current step, a count, the elapsed time and an ETA."""

from __future__ import annotations

import sys


def wanted(quiet: bool) -> bool:
    """Progress is shown unless --quiet or the output is not a terminal (a log, a pipe, CI)."""
    return not quiet and sys.stderr.isatty()


class StepProgress:
    """A bar counting ``total`` steps of ``unit``, naming the current one. Silent unless
    ``enabled`` and (when ``terminal_only``) stderr is a terminal. Usable as a context manager."""

    def __init__(
        self,
        enabled: bool,
        total: int,
        label: str,
        unit: str = "steps",
        *,
        terminal_only: bool = True,
        transient: bool = True,
    ):
        self.bar = None
        if not enabled or (terminal_only and not sys.stderr.isatty()):
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
            TextColumn(unit),
            TimeElapsedColumn(),
            TextColumn("ETA"),
            TimeRemainingColumn(),
            console=Console(stderr=True),
            transient=transient,
        )
        self.bar.start()
        self.task = self.bar.add_task(label, total=total)

    def show(self, what: str) -> None:
        if self.bar is not None:
            self.bar.update(self.task, description=what)

    def advance(self, k: int = 1) -> None:
        if self.bar is not None:
            self.bar.advance(self.task, k)

    def step(self, what: str) -> None:
        """The next step begins: count the previous one and name this one."""
        if self.bar is not None:
            self.bar.update(self.task, description=what, advance=1)

    def print(self, line: str) -> None:
        """A line above the bar (nothing without one)."""
        if self.bar is not None:
            self.bar.console.print(line, highlight=False)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.stop()
            self.bar = None

    def __enter__(self) -> StepProgress:
        return self

    def __exit__(self, *exc) -> None:
        self.close()
