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


@app.command("sweep")
def sweep_command(
    config: Path = typer.Argument(..., help="The sweep file (TOML): run, design, parameters."),
    out: Path = typer.Option(Path("sweep-out"), "--out", "-o", help="Folder for the results."),
    scheduler: str | None = typer.Option(
        None, "--scheduler", help="Dask scheduler address (tcp://host:8786); default: local."
    ),
    workers: int | None = typer.Option(
        None, "--workers", help="Local processes (default: the file's, else all cores)."
    ),
    n: int | None = typer.Option(None, "--n", help="Number of draws (overrides the file)."),
    seed: int | None = typer.Option(None, "--seed", help="Seed (overrides the file)."),
    bound: float | None = typer.Option(
        None, "--bound", help="Error bound on the primary metric (overrides the file)."
    ),
    figures: bool = typer.Option(True, "--figures/--no-figures", help="Write the figures."),
) -> None:
    """Run a robustness sweep from a TOML file; write the table (CSV, Parquet), a summary
    (quantiles per compensator, fraction within the bound), a sensitivity ranking and figures."""
    from rich.markup import escape

    from .sweep import SweepError, sweep
    from .sweep.toml import read_sweep_file

    err = Console(stderr=True)
    try:
        spec = read_sweep_file(config)
        engine = scheduler or spec.scheduler or "local"
        res = sweep(
            spec.run,
            spec.design,
            n=n if n is not None else spec.n,
            seed=seed if seed is not None else spec.seed,
            engine=engine,
            workers=workers if workers is not None else spec.workers,
            batch_size=spec.batch_size,
            on_error=spec.on_error,
            retries=spec.retries,
            progress=True,
        )
        the_bound = bound if bound is not None else spec.bound
        written = res.save(out, bound=the_bound, figures=figures)
    except (ValueError, ConnectionError, SweepError) as exc:
        err.print(f"[red]error:[/red] {escape(str(exc))}", soft_wrap=True, highlight=False)
        raise typer.Exit(2) from None

    metric = res.primary_metric()
    summary = res.summary(the_bound)
    summary = summary[summary["metric"] == metric]
    table = Table(title=f"{metric} over {res.n_runs} runs ({res.design}, seed {res.seed})")
    table.add_column("compensator")
    for col in ("median", "q95", "max"):
        table.add_column(col, justify="right")
    has_bound = "within_bound" in summary
    if has_bound:
        table.add_column(f"<= {summary['bound'].iloc[0]:g}", justify="right")
    for _, row in summary.iterrows():
        cells = [f"{row[c]:.4g}" for c in ("median", "q95", "max")]
        if has_bound:
            cells.append(f"{100 * row['within_bound']:.0f} %")
        table.add_row(str(row["compensator"]), *cells)
    console.print(table)
    try:
        sens = res.sensitivity(metrics=metric)
    except ValueError:
        sens = None
    if sens is not None and len(sens):
        value = "ST" if "ST" in sens else "coefficient"
        for comp, g in sens.groupby("compensator", sort=False):
            ranking = ", ".join(f"{r['parameter']} ({r[value]:+.2f})" for _, r in g.iterrows())
            note = ""
            if "r2" in g and g["r2"].iloc[0] < 0.5:
                note = (
                    f" [dim](linear R2 = {g['r2'].iloc[0]:.2f}: effects are non-linear, "
                    "e.g. error growing both ways from nominal; design = 'saltelli' gives "
                    "Sobol indices)[/dim]"
                )
            console.print(f"most influential on {metric} ({comp}): {ranking}{note}")
    e = res.engine
    console.print(
        f"{res.n_runs} runs on {e['engine']} ({e['workers']} worker"
        f"{'s' if e['workers'] != 1 else ''}) in "
        f"{e['wall_seconds']:.1f} s, {e['runs_per_second']:.1f} runs/s"
    )
    console.print(f"wrote {len(written)} files to {out}:")
    for path in written:
        console.print(f"  {path}", soft_wrap=True, highlight=False)


def main() -> None:
    app()


if __name__ == "__main__":
    main()
