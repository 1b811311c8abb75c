"""The `tendonsheath` command."""

from __future__ import annotations

from pathlib import Path

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
) -> None:
    """Run the built-in virtual bench and write metrics.json and figures to OUT."""
    from .demo import run_demo

    with console.status("simulating") as status:
        metrics = run_demo(out, progress=lambda name: status.update(f"simulating {name}"))
    table = Table(title="hysteresis models on the standard input")
    table.add_column("model")
    table.add_column("output range", justify="right")
    table.add_column("loop width (last cycle)", justify="right")
    table.add_column("simulate time", justify="right")
    for name, m in metrics["models"].items():
        table.add_row(
            name,
            f"{m['output_min']:.3f} .. {m['output_max']:.3f}",
            f"{m['loop_width_last_cycle']:.4f}",
            f"{1e3 * m['simulate_seconds']:.2f} ms",
        )
    console.print(table)
    console.print("wrote:")
    for path in metrics["written"]:
        console.print(f"  {path}")


def main() -> None:
    app()


if __name__ == "__main__":
    main()
