"""The `tendonsheath` command."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import typer
from rich.console import Console
from rich.table import Table

app = typer.Typer(
    help="Model, identify and compensate tendon-sheath mechanisms.",
    no_args_is_help=True,
    add_completion=False,
)
console = Console()


@app.callback()
def _root() -> None:
    """Model, identify and compensate tendon-sheath mechanisms."""


@app.command()
def demo(
    out: Path = typer.Option(Path("demo-out"), "--out", "-o", help="Folder for the results."),
    scale: float = typer.Option(1.0, help="Run length factor (below 1: a quicker, shorter run)."),
    scenario: list[str] = typer.Option(
        None, "--scenario", "-s", help="Only these scenarios (do2015, sun2015, lau2015)."
    ),
    seed: int = typer.Option(0, help="Seed of the random route changes and sensor noise."),
) -> None:
    """Run the virtual bench (the three seed experiments) and write report.html,
    metrics.json and the figures to OUT."""
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

    from .demo import run_demo

    if not scale > 0:
        _fail("--scale must be > 0")
    steps = 1 + 3 * len(scenario or ["do2015", "sun2015", "lau2015"]) + 1
    with Progress(
        TextColumn("{task.description}"),
        BarColumn(),
        TimeElapsedColumn(),
        console=console,
        transient=True,
    ) as bar:
        task = bar.add_task("starting", total=steps)

        def tick(message: str) -> None:
            bar.update(task, description=message, advance=1)

        try:
            written = run_demo(
                out, scale=scale, scenarios=scenario or None, progress=tick, seed=seed
            )
        except ValueError as exc:
            _fail(str(exc))
    data = written["data"]
    for name, comps in data["scenarios"].items():
        table = Table(title=f"{name} ({written['timings'][name]:.1f} s)")
        table.add_column("compensator")
        for col in ("mse [rad^2]", "rmse [deg]", "percent error"):
            table.add_column(col, justify="right")
        for comp, m in comps.items():
            table.add_row(
                comp,
                f"{m['mse']:.3e}",
                f"{np.degrees(m['rmse']):.3f}",
                f"{m['percent_error']:.2f} %",
            )
        console.print(table)
    console.print(f"wrote {written['report']}")
    console.print(f"wrote {written['metrics']}")
    console.print(f"wrote {len(written['figures'])} figures to {out}")


def _fail(message: str) -> None:
    console.print(f"[red]error:[/red] {message}")
    raise typer.Exit(code=2)


def main() -> None:
    app()


if __name__ == "__main__":
    main()
