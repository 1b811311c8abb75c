"""The `tendonsheath` command."""

from __future__ import annotations

import functools
import warnings
from importlib.metadata import version as package_version
from pathlib import Path
from typing import NoReturn

import numpy as np
import typer
from rich.console import Console
from rich.table import Table
from typer.core import TyperCommand, TyperOption

from .._util.extras import MissingExtraError, require_plotly
from .._util.outputs import check_image_file, check_output_file, check_output_folder
from ..identify.core import takes_curve_angle
from ..identify.diagnostics import IdentifiabilityWarning
from ..identify.fit import GIVEN_CLASS

_display_type = TyperOption.display_type_rich


def _no_type_for_flags(self, ctx):
    """A flag takes no value: typer's "<bool>" in every --help would say it does."""
    return None if self.is_flag else _display_type(self, ctx)


TyperOption.display_type_rich = _no_type_for_flags  # type: ignore[method-assign]  # see above

app = typer.Typer(
    help="Model, identify and compensate tendon-sheath mechanisms.",
    no_args_is_help=True,
    add_completion=False,
)
console = Console()


def _one_paragraph(fn):
    """The command's docstring as one paragraph: typer keeps a source line break, which then
    splits a sentence in the middle in every --help."""
    fn.__doc__ = " ".join((fn.__doc__ or "").split())
    return fn


def _quiet_option():
    return typer.Option(
        False, "--quiet", "-q", help="No progress bar (none either when not on a terminal)."
    )


_ANGLE_UNIT_HELP = "Unit of the angles shown in the tables and the report: deg or rad."


def _angle_unit(unit: str) -> str:
    if unit not in ("deg", "rad"):
        _fail(f"--angle-unit must be deg or rad (got {unit!r})")
    return unit


def _check_seed(seed: int | None) -> None:
    """--seed: what numpy's generators take, checked before any work."""
    if seed is not None and not 0 <= seed < 2**32:
        _fail(f"--seed must be in [0, 2**32) (got {seed})")


def _in_unit(value_rad: float, unit: str, squared: bool = False) -> float:
    factor = (180 / np.pi if unit == "deg" else 1.0) ** (2 if squared else 1)
    return value_rad * factor


def _check_finite(what: str, values: dict) -> None:
    """A metric that is not finite is an error (exit 2), never a result."""
    bad = {k: v for k, v in values.items() if v is None or not np.isfinite(v)}
    if bad:
        listed = ", ".join(f"{k} = {v}" for k, v in bad.items())
        _fail(f"{what}: {listed} is not finite (data too small, too large or constant?)")


# click's usage errors (typer.BadParameter and its kin); typer >= 0.20 vendors click, so the
# class is found through typer rather than imported from a click that may not be installed
_CLICK_ERROR = next(c for c in typer.BadParameter.__mro__ if c.__name__ == "ClickException")


def _no_traceback(command):
    """Every way a command ends is one line, never a traceback. Ctrl-C: exit code 130
    (128 + SIGINT); outputs are written atomically, so none is left half-written. A
    ValueError, OverflowError or OSError no check caught earlier is bad input or a file the
    system refused, and a MissingExtraError a feature used without its extra: "error: ..." and
    exit 2. Anything else is a bug: its type and message on one line, said to be a bug, and
    exit 1."""

    @functools.wraps(command)
    def run(*args, **kwargs):
        name = command.__name__.removesuffix("_command")
        try:
            with warnings.catch_warnings():
                warnings.showwarning = _show_warning
                return command(*args, **kwargs)
        except KeyboardInterrupt:
            Console(stderr=True).print(
                f"interrupted (Ctrl-C): {name} stopped; no output file is left half-written",
                highlight=False,
            )
            raise typer.Exit(130) from None
        except (typer.Exit, typer.Abort, _CLICK_ERROR):
            raise  # typer's own ends: an exit code, a usage error
        except (ValueError, OverflowError, OSError, MissingExtraError) as exc:
            _fail(exc)
        except Exception as exc:  # a bug: said so in one line, not hidden
            _fail_bug(name, exc)

    return run


def _show_warning(message, category, filename, lineno, file=None, line=None) -> None:
    """A warning as one line on stderr, its category named: "Warning (UnitWarning): ...", not
    Python's "FILE:LINE: UnitWarning: ..." with a line of the package's (or typer's) source."""
    from rich.markup import escape

    text = " ".join(str(message).split())
    Console(stderr=True).print(
        f"[yellow]Warning ({escape(category.__name__)}):[/yellow] {escape(text)}",
        soft_wrap=True,
        highlight=False,
    )


def _fail_bug(command: str, exc: Exception) -> NoReturn:
    """The last resort: an exception no check expected, in one line, and exit 1."""
    from rich.markup import escape

    console.print(
        f"[red]error:[/red] {escape(type(exc).__name__)}: {escape(str(exc))} -- a bug in "
        f"`tendonsheath {command}` (an input it should have checked, or worse): please report "
        "it with the command line and its input files",
        soft_wrap=True,
        highlight=False,
    )
    raise typer.Exit(code=1)


def _print_notes(log) -> None:
    """The data-quality notes read_log collected (duplicates, gaps, irregular sampling)."""
    for note in log.notes:
        console.print(f"[yellow]{log.path}:[/yellow] {_cli_note(note)}", soft_wrap=True)


def _print_version(value: bool) -> None:
    if value:
        typer.echo(f"tendonsheath {package_version('tendonsheath')}")
        raise typer.Exit()


@app.callback()
def _root(
    version: bool = typer.Option(
        False,
        "--version",
        callback=_print_version,
        is_eager=True,
        help="Print the version and exit.",
    ),
) -> None:
    """Model, identify and compensate tendon-sheath mechanisms."""


@app.command()
@_one_paragraph
@_no_traceback
def demo(
    out: Path = typer.Option(Path("demo-out"), "--out", "-o", help="Folder for the results."),
    scale: float = typer.Option(1.0, help="Run length factor (below 1: a quicker, shorter run)."),
    scenario: list[str] = typer.Option(
        None, "--scenario", "-s", help="Only these scenarios (do2015, sun2015, lau2015)."
    ),
    seed: int = typer.Option(0, help="Seed of the random route changes and sensor noise."),
    robustness: bool = typer.Option(
        True,
        "--robustness/--no-robustness",
        help="Also run the Monte Carlo robustness study (200 draws x scale, at least 20).",
    ),
    angle_unit: str = typer.Option("deg", "--angle-unit", help=_ANGLE_UNIT_HELP),
    workers: int | None = typer.Option(
        None,
        "--workers",
        help="Processes the scenarios run in, side by side (default: one per core; 1: one "
        "after the other in this process). The results do not depend on it.",
    ),
    quiet: bool = _quiet_option(),
) -> None:
    """Run the virtual bench (the three seed experiments) and write report.html,
    metrics.json and the figures to OUT."""
    from .._util.progress import StepProgress, wanted
    from ..bench.scenarios import SCENARIOS
    from .demo import run_demo

    if not scale > 0 or not np.isfinite(scale):
        _fail(f"--scale must be a finite number > 0 (got {scale})")
    unit = _angle_unit(angle_unit)
    _check_seed(seed)
    if workers is not None and workers < 1:
        _fail(f"--workers must be at least 1 (got {workers})")
    unknown = [n for n in scenario or [] if n not in SCENARIOS]
    if unknown:
        _fail(f"unknown scenario(s) {unknown}; known: {list(SCENARIOS)}")
    _checked(check_output_folder, out)
    require_plotly()  # the report needs it: said before the runs start
    steps = 1 + 3 * len(scenario or SCENARIOS) + 1 + int(robustness)
    with StepProgress(wanted(quiet), steps, "starting") as bar:
        # the calibrations' identifiability warnings are part of the result (the report's
        # honesty panel lists the parameters at bounds): collected, then printed once each
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", IdentifiabilityWarning)
            try:
                written = run_demo(
                    out,
                    scale=scale,
                    scenarios=scenario or None,
                    progress=bar.step,
                    seed=seed,
                    robustness=robustness,
                    angle_unit=unit,
                    workers=workers,
                )
            except ValueError as exc:
                _fail(str(exc))
    for message in dict.fromkeys(
        str(w.message) for w in caught if issubclass(w.category, IdentifiabilityWarning)
    ):
        console.print(f"[yellow]calibration: {message}[/yellow]")
    _print_demo_tables(written, unit)
    console.print(f"wrote {written['report']}")
    console.print(f"wrote {written['metrics']}")
    console.print(f"wrote {len(written['figures'])} figures to {out}")


def _print_demo_tables(written: dict, unit: str) -> None:
    data = written["data"]
    for name, comps in data["scenarios"].items():
        table = Table(title=f"{name} ({written['timings'][name]:.1f} s)")
        table.add_column("compensator")
        for col in (f"mse ({unit}^2)", f"rmse ({unit})", "percent error (%)"):
            table.add_column(col, justify="right")
        for comp, m in comps.items():
            _check_finite(f"{name} {comp}", {k: m.get(k) for k in ("mse", "rmse")})
            table.add_row(
                comp,
                f"{_in_unit(m['mse'], unit, squared=True):.3e}",
                f"{_in_unit(m['rmse'], unit):.4g}",
                f"{m['percent_error']:.2f}",
            )
        _print_table(table)
    if "robustness" in data:
        runs = data["robustness"]["runs"]
        table = Table(title=f"robustness: mse ({unit}^2) over {runs} perturbed plants")
        for col in ("compensator", "median", "95 %", "share <= 1e-4 rad^2 (%)"):
            table.add_column(col, justify="left" if col == "compensator" else "right")
        for comp, q in data["robustness"]["compensators"].items():
            table.add_row(
                comp,
                f"{_in_unit(q['median'], unit, squared=True):.3e}",
                f"{_in_unit(q['q95'], unit, squared=True):.3e}",
                f"{100 * q.get('within_bound', float('nan')):.0f}",
            )
        _print_table(table)


def _checked(check, *args, **kwargs):
    """Run an input check; its ValueError is the one-line error."""
    try:
        return check(*args, **kwargs)
    except ValueError as exc:
        _fail(exc)


def _same_file(a: Path, b: Path) -> bool:
    """``a`` and ``b`` name one file (the same path, a link or a hard link to it)."""
    import os

    if a.resolve() == b.resolve():
        return True
    try:
        return a.exists() and b.exists() and os.path.samefile(a, b)
    except OSError:
        return False


def _refuse_overwriting(out: Path, what: str, inputs: dict) -> None:
    """``out`` (option ``what``) must not be one of the ``inputs`` (role -> path): writing
    it would destroy what the command reads."""
    for role, path in inputs.items():
        if path is not None and _same_file(out, Path(path)):
            _fail(f"{what} {out} is the {role}: writing it would destroy it; give another name")


def _note(text: str) -> None:
    """A suspicious but legal run: said once, in yellow, and the command goes on."""
    console.print(f"[yellow]note:[/yellow] {text}", soft_wrap=True, highlight=False)


def _note_suspicious(data: list[Path], validate: list[Path]) -> None:
    """Notes for the same file twice and validating on a training file (the input and the
    output one column: read_log refuses it)."""
    seen: list[Path] = []
    for path in data:
        if any(_same_file(path, p) for p in seen):
            _note(f"{path} is given twice: its recording counts twice")
        seen.append(path)
    for path in validate:
        if any(_same_file(path, p) for p in data):
            _note(
                f"validating on {path}, a training file: its validation error is not a "
                "held-out error"
            )


@app.command()
@_one_paragraph
@_no_traceback
def bench(
    scenario: Path = typer.Argument(
        ...,
        help="Scenario file (TOML): plant, route schedule, "
        "load, motor, sensor, reference, compensators.",
    ),
    out: Path = typer.Option(Path("bench-out"), "--out", "-o", help="Folder for the results."),
    angle_unit: str = typer.Option("deg", "--angle-unit", help=_ANGLE_UNIT_HELP),
    quiet: bool = _quiet_option(),
) -> None:
    """Run a user scenario on the virtual bench: calibrate, compare the compensators, and
    write report.html, metrics.json and the figures to OUT."""
    from .._util.progress import StepProgress, wanted
    from ..bench.user_scenario import ScenarioError, load, run_user_scenario
    from ..report.build import write

    unit = _angle_unit(angle_unit)
    require_plotly()  # the report is written last: say so before the runs, not after
    try:
        sc = load(scenario)
    except ScenarioError as exc:
        _fail(exc)
    _checked(check_output_folder, out)
    steps = len(sc.compensators) + 2  # calibration, each compensator, honesty panel
    with StepProgress(wanted(quiet), steps, "starting") as bar:
        try:
            result = run_user_scenario(sc, progress=bar.step)
        except ScenarioError as exc:
            _fail(exc)
    for row in result.table:
        _check_finite(f"{sc.source} {row['compensator']}", {k: row[k] for k in ("mse", "rmse")})
    written = write(out, [result], None, title=sc.title, angle_unit=unit)
    table = Table(title=sc.title)
    for col in (
        "compensator",
        f"mse ({unit}^2)",
        f"rmse ({unit})",
        "percent error (%)",
        "mse vs none (x)",
    ):
        table.add_column(col, justify="left" if col == "compensator" else "right")
    for row in result.table:
        table.add_row(
            row["compensator"],
            f"{_in_unit(row['mse'], unit, squared=True):.3e}",
            f"{_in_unit(row['rmse'], unit):.4g}",
            f"{row['percent_error']:.2f}",
            f"{row['improvement']:.1f}",
        )
    _print_table(table)
    console.print(f"wrote {written['report']} and {written['metrics']}")


_TIME_HELP = (
    "Time column (s). In a ROS bag: header, receive or /topic:field (default: header stamps "
    "where the messages have them, else the receive time)."
)


def _print_table(table: Table) -> None:
    """A table on stdout; off a terminal (a log, a pipe) 160 columns wide, where rich would fit
    80 and cut the names."""
    if console.is_terminal:
        console.print(table)
    else:
        Console(file=console.file, width=160).print(table)


_TIME_UNIT_HELP = (
    "Unit of a numeric time column: s, ms, us or ns (integer epoch nanoseconds: ns). Times "
    "are converted to seconds, so a dynamic model's time constants are in seconds."
)
_TIME_UNIT_OPTION = typer.Option("s", "--time-unit", help=_TIME_UNIT_HELP)
_PREDICT_TIME_UNIT_OPTION = typer.Option(
    None, "--time-unit", help="Unit of a numeric time column: s, ms, us or ns (default: as fitted)."
)
_PREDICT_INPUT_OPTION = typer.Option(None, "--input", help="Input column (default: as fitted).")
_PREDICT_OUTPUT_OPTION = typer.Option(
    None, "--output", help="Measured output column, if any (default: as fitted)."
)
_STANDARD_ERRORS_OPTION = typer.Option(
    "linearised",
    "--standard-errors",
    help="linearised, bootstrap (residual blocks) or bootstrap-recordings (one resample "
    "draws whole recordings).",
)


def _data_columns(time_col, time_unit: str, **columns) -> dict:
    """read_log's column arguments: the named columns, and the time unit where not seconds."""
    out = dict(time=time_col, **columns)
    if time_unit != "s":
        out["time_unit"] = time_unit
    return out


def _fail(reason) -> NoReturn:
    """One-line reason on bad input, and a non-zero exit (2)."""
    from rich.markup import escape

    # escaped: "[plant]" or "[deg]" in a reason is text, not rich markup
    console.print(f"[red]error:[/red] {escape(str(reason))}", soft_wrap=True, highlight=False)
    raise typer.Exit(code=2)


# the long options of `identify`, kept out of its signature
_IDENTIFY_LOAD_OPTION = typer.Option(
    None,
    "--load",
    help="Measured load column (e.g. a jaw torque; in a ROS bag /topic:field): the model "
    "becomes Loaded(MODEL), its load terms identified with it.",
)
_BOUNDS_OPTION = typer.Option(
    None,
    "--bounds",
    help="A parameter's search bounds, NAME=LO:HI (repeat for several), e.g. --bounds n=0.5:20.",
)


def _parsed_bounds(items: list[str]) -> dict[str, tuple[float, float]]:
    """--bounds NAME=LO:HI ... as identify's ``bounds`` (a one-line error otherwise)."""
    out = {}
    for item in items:
        name, _, rng = item.partition("=")
        lo, _, hi = rng.partition(":")
        try:
            low, high = float(lo), float(hi)
        except ValueError:
            _fail(f"--bounds: expected NAME=LO:HI with numbers, e.g. n=0.5:20 (got {item!r})")
        if not name.strip() or not (np.isfinite(low) and np.isfinite(high) and low < high):
            _fail(f"--bounds: expected NAME=LO:HI with finite LO < HI (got {item!r})")
        out[name.strip()] = (low, high)
    return out


@app.command()
@_one_paragraph
@_no_traceback
def identify(
    data: list[Path] = typer.Argument(
        ...,
        help="Data file(s): CSV/TSV with header, NPY, NPZ, HDF5, Excel, ROS bag (.bag, .db3, "
        ".mcap or a bag folder).",
    ),
    model: str = typer.Option(
        ...,
        "--model",
        "-m",
        help="Model class or short name, e.g. BoucWenBacklash, bwb, pi, gpi, bwb+poly3.",
    ),
    input_col: str = typer.Option(
        ...,
        "--input",
        help="Input column (motor position); in a ROS bag /topic:field, e.g. "
        "/motor/joint_states:position[0].",
    ),
    output_col: str = typer.Option(
        ..., "--output", help="Output column (tip position); in a ROS bag /topic:field."
    ),
    time_col: str | None = typer.Option(None, "--time", help=_TIME_HELP),
    time_unit: str = _TIME_UNIT_OPTION,
    curve_angle: str | None = typer.Option(
        None, "--curve-angle", help="Curve-angle column, or a number (rad)."
    ),
    load_col: str | None = _IDENTIFY_LOAD_OPTION,
    bounds: list[str] = _BOUNDS_OPTION,
    validate: Path | None = typer.Option(None, "--validate", help="Data file to validate on."),
    out: Path = typer.Option(Path("model.json"), "--out", "-o", help="Where to save the model."),
    warmup: int = typer.Option(0, "--warmup", help="Samples per recording not fitted."),
    seed: int = typer.Option(0, "--seed", help="Seed of the global search and the bootstrap."),
    maxiter: int = typer.Option(100, "--maxiter", help="Generations of the global search."),
    report: Path | None = typer.Option(
        None, "--report", help="Write a figure of the fit here (.png, .pdf, .svg, ...)."
    ),
    standard_errors: str = _STANDARD_ERRORS_OPTION,
    resamples: int | None = typer.Option(
        None, "--resamples", help="Bootstrap resamples (default 200)."
    ),
    time_budget: float | None = typer.Option(
        None,
        "--time-budget",
        help="Seconds of wall clock for the search and the refinement; the best model found "
        "by then is kept and the output says so.",
    ),
    quiet: bool = _quiet_option(),
) -> None:
    """Fit MODEL to DATA and save it as JSON; print the fit table and the validation error."""
    from .._util.progress import wanted

    _check_identify_options(out, report, maxiter, warmup, seed)
    candidate = _checked(_model_spec, model)
    columns = _data_columns(
        time_col, time_unit, input=input_col, output=output_col, curve_angle=curve_angle
    )
    if load_col is not None:
        candidate = _checked(_loaded_spec, candidate)
        columns["load"] = load_col
    _check_flags_apply(model, candidate, curve_angle, resamples, standard_errors)
    search = {
        "warmup": warmup,
        "seed": seed,
        "maxiter": maxiter,
        "progress": wanted(quiet),
        "standard_errors": standard_errors,
        "bootstrap": resamples,
        "time_budget": time_budget,
    }
    if bounds:
        search["bounds"] = _parsed_bounds(bounds)
    fit, val, n_logs = _checked(_fit_logs, candidate, data, validate, columns, search)
    _save_fit(out, fit, val, columns)
    _print_fit(fit, n_logs, output_col)
    _print_validation(val, validate, output_col)
    if report is not None:
        console.print(f"report: {fit.report(report)}")
    console.print(f"model saved to {out}")


def _print_validation(val: dict | None, validate: Path | None, output_col: str) -> None:
    """The validation line of ``identify`` (nothing without --validate)."""
    if val is not None:
        console.print(
            f"validation on {validate}: rmse {val['rmse']:.4g} ({output_col} units)   "
            f"nrmse {100 * val['nrmse']:.3f} %   fit {val['fit_percent']:.2f} %"
        )


def _read_logs(paths, columns: dict, **options) -> list:
    """``io.read_log`` of each file, with the named ``columns`` (time, input, output and
    curve_angle) and the other ``options``."""
    from .. import io

    return [io.read_log(path, **columns, **options) for path in paths]


def _fit_logs(candidate, data: list[Path], validate: Path | None, columns: dict, search: dict):
    """Fit ``candidate`` to the recordings in ``data`` (``search``: identify's options) and
    validate it on ``validate``: (fit, validation metrics or None, number of recordings).
    A fit or a validation error that is not finite is an error (exit 2)."""
    from ..identify import identify as run_identify
    from ..models import Loaded

    _note_suspicious(data, [validate] if validate else [])
    logs = _read_logs(data, columns)
    vlog = _read_logs([validate], columns)[0] if validate is not None else None
    for log in logs + ([vlog] if vlog is not None else []):  # before the (long) fitting
        _print_notes(log)
    with warnings.catch_warnings():  # printed below with the diagnostics
        warnings.simplefilter("ignore", IdentifiabilityWarning)
        fit = run_identify(candidate, recordings=logs, **search)
    val = None
    if vlog is not None and vlog.load is not None and isinstance(fit.model, Loaded):
        from ..identify.fit import metrics

        val = metrics(vlog.y, fit.model.simulate(vlog.t, vlog.x, load=vlog.load))
    elif vlog is not None:
        val = fit.validate(vlog.t, vlog.x, vlog.y, vlog.curve_angle)
    _check_finite("the fit", {"rmse": fit.rmse, "nrmse": fit.nrmse})
    if val is not None:
        _check_finite(f"validation on {validate}", {k: val[k] for k in ("rmse", "nrmse")})
    return fit, val, len(logs)


def _check_identify_options(
    out: Path, report: Path | None, maxiter: int, warmup: int, seed: int
) -> None:
    """One-line errors for identify's output files and search options, before any work."""
    from ..identify.core import check_search_options

    _check_seed(seed)
    _checked(check_output_file, out)
    if out.suffix and out.suffix.lower() != ".json":  # model.csv would hold JSON
        _fail(f"--out {out}: a model is saved as JSON: give a .json name (got {out.suffix!r})")
    if report is not None:
        _checked(check_image_file, report)
    _checked(
        check_search_options, maxiter=maxiter, popsize=15, tol=0.01, workers=None, warmup=warmup
    )


def _check_flags_apply(model: str, candidate, curve_angle, resamples, standard_errors: str):
    """identify's flags that do not apply to what was asked: a one-line error, never a flag
    silently ignored (--resamples without a bootstrap, --curve-angle to a model without one)."""
    if resamples is not None and not standard_errors.startswith("bootstrap"):
        _fail(
            f"--resamples applies to --standard-errors bootstrap or bootstrap-recordings only "
            f"(got {standard_errors}): give one of those, or leave --resamples out"
        )
    if curve_angle is not None and not takes_curve_angle(getattr(candidate, "base", candidate)):
        _fail(
            f"--curve-angle: {model} takes no curve angle (CurveAngleModel does, `curve`): "
            "leave --curve-angle out, or name a model that uses it"
        )


def _loaded_spec(candidate):
    """Loaded(candidate): a class name, a class or a Chain as the base."""
    from ..models import Loaded
    from ..models.base import _REGISTRY

    if isinstance(candidate, str):
        candidate = _REGISTRY[candidate]
    if isinstance(candidate, Loaded) or candidate is Loaded:
        raise ValueError("--load makes the model Loaded(MODEL): name the base model alone")
    return Loaded(candidate)


def _model_spec(name: str):
    """A registered class name as it is (any identifiable model), else compare's names
    (bwb, pi, gpi, bw, curve, bwb+poly3, lag1+bwb, ...)."""
    from ..models.base import _REGISTRY
    from .compare import parse_model

    return name if name in _REGISTRY else parse_model(name)


def _save_fit(out: Path, fit, val, data_columns: dict) -> None:
    from .._util.atomic import write_json

    record = fit.model.to_dict()
    record["data"] = data_columns
    record["fit"] = {k: v for k, v in fit.to_dict().items() if k != "model"}
    if val is not None:
        record["validation"] = val
    out.parent.mkdir(parents=True, exist_ok=True)
    write_json(out, record)


def _print_fit(fit, n_logs: int, output_col: str) -> None:
    table = Table(title=f"{type(fit.model).__name__} fitted to {n_logs} recording(s)")
    table.add_column("parameter")
    table.add_column("value", justify="right")
    table.add_column("std. error", justify="right")
    for row in fit.table():
        table.add_row(*row)
    _print_table(table)
    console.print(
        f"rmse {fit.rmse:.4g} ({output_col} units)   nrmse {100 * fit.nrmse:.3f} %   "
        f"fit {fit.fit_percent:.2f} %   ({fit.evaluations} evaluations, {fit.seconds:.2f} s)"
    )
    console.print(f"standard errors: {fit.se_description()}, {GIVEN_CLASS}")
    if fit.stopped_on_budget:
        console.print("stopped by the time budget: the best model found by then")
    for name, g in fit.groups.items():  # identified groups (e.g. CurveAngleModel, one angle)
        se = f" +- {g['se']:.4g}" if g.get("se") is not None else " (held)"
        console.print(f"group {name} = {g['value']:.6g}{se} {g.get('unit', '')}")
    for line in fit.diagnostics.lines():
        if line.startswith("WARNING: "):
            console.print(f"[yellow]warning:[/yellow] {line.removeprefix('WARNING: ')}")
        else:
            console.print(f"identifiability: {line}", soft_wrap=True)


@app.command()
@_one_paragraph
@_no_traceback
def predict(
    model_file: Path = typer.Argument(..., help="Model JSON written by `identify`."),
    data: Path = typer.Argument(..., help="Data file with the input column."),
    out: Path = typer.Option(Path("pred.csv"), "--out", "-o", help="CSV of predictions."),
    input_col: str | None = _PREDICT_INPUT_OPTION,
    output_col: str | None = _PREDICT_OUTPUT_OPTION,
    time_col: str | None = typer.Option(None, "--time", help="Time column (default: as fitted)."),
    time_unit: str | None = _PREDICT_TIME_UNIT_OPTION,
    curve_angle: str | None = typer.Option(
        None, "--curve-angle", help="Curve-angle column or number (default: as fitted)."
    ),
    load_col: str | None = typer.Option(
        None, "--load", help="Measured load column, for a Loaded model (default: as fitted)."
    ),
    warmup: int = typer.Option(0, "--warmup", help="Samples left out of the rmse."),
) -> None:
    """Predict the output of a saved model for DATA; print the rmse if the output is there."""
    from .. import io
    from ..identify.fit import metrics, simulate_model
    from ..models import Loaded, load_model

    _check_predict_options(out, data, model_file, warmup)
    try:
        model = load_model(model_file)
        _check_predict_flags(model, curve_angle, load_col)
        saved = _saved_columns(model_file)
        input_col = input_col or saved.get("input")
        time_col = time_col or saved.get("time")
        time_unit = time_unit or saved.get("time_unit") or "s"
        curve_angle = curve_angle or saved.get("curve_angle")
        wanted_output = output_col or saved.get("output")
        load_col = load_col or saved.get("load")
        if input_col is None:
            raise ValueError("name the input column with --input")
        if isinstance(model, Loaded) and load_col is None:
            raise ValueError("a Loaded model needs the measured load: name its column with --load")
        table_columns = io.columns(data)
        has_output = wanted_output is not None and (
            wanted_output in table_columns or output_col is not None
        )
        log = io.read_log(
            data,
            time=time_col,
            input=input_col,
            output=wanted_output if has_output else None,
            curve_angle=curve_angle,
            load=load_col if isinstance(model, Loaded) else None,
            time_unit=time_unit,
        )
        _print_notes(log)
        if log.y is not None and warmup >= log.x.size:
            raise ValueError(f"--warmup {warmup} leaves none of the {log.x.size} samples")
        if isinstance(model, Loaded):
            y_hat = np.asarray(model.simulate(log.t, log.x, load=log.load), dtype=float)
        else:
            y_hat = simulate_model(model, log.t, log.x, log.curve_angle)
    except ValueError as exc:
        _fail(exc)
    with np.errstate(over="ignore", invalid="ignore"):  # a non-finite metric: error below
        m = metrics(log.y[warmup:], y_hat[warmup:]) if log.y is not None else None
    if m is not None:
        _check_finite(f"prediction of {data}", {k: m[k] for k in ("rmse", "nrmse")})
    cols = {}
    if log.t is not None:
        cols[time_col or "time"] = log.t  # a bag has a time without a time column
    cols[input_col] = log.x
    if log.load is not None and load_col is not None:
        cols[load_col] = log.load
    if log.y is not None and wanted_output is not None:  # an output was read: it was named
        cols[wanted_output] = log.y
    cols["predicted"] = y_hat
    io.write_csv(out, cols)
    console.print(f"wrote {len(y_hat)} predictions to {out}")
    if m is not None:
        console.print(
            f"rmse {m['rmse']:.4g} ({wanted_output} units)   nrmse {100 * m['nrmse']:.3f} %   "
            f"fit {m['fit_percent']:.2f} %"
        )


def _check_predict_flags(model, curve_angle: str | None, load_col: str | None) -> None:
    """--curve-angle and --load given to a saved model that takes neither: a ValueError, not
    a flag ignored."""
    from ..models import Loaded

    name = type(model).__name__
    if curve_angle is not None and not takes_curve_angle(getattr(model, "base", model)):
        raise ValueError(f"--curve-angle: the saved {name} takes no curve angle; leave it out")
    if load_col is not None and not isinstance(model, Loaded):
        raise ValueError(
            f"--load: the saved {name} takes no measured load (a Loaded model does); leave it out"
        )


def _check_predict_options(out: Path, data: Path, model_file: Path, warmup: int) -> None:
    """--warmup and --out of ``predict``: a CSV that is neither of its inputs."""
    if warmup < 0:
        _fail(f"--warmup must be >= 0 (got {warmup})")
    _checked(check_output_file, out, suffixes={"csv", "txt"})
    _refuse_overwriting(out, "--out", {"data file": data, "model file": model_file})


def _saved_columns(model_file: Path) -> dict:
    """The column names `identify` saved beside the model ("data"), if any."""
    import json

    try:
        saved = json.loads(model_file.read_text()).get("data")
    except (OSError, json.JSONDecodeError):
        return {}
    if saved is None:
        return {}
    if not isinstance(saved, dict):
        raise ValueError(f"{model_file}: 'data' must be an object of column names (got {saved!r})")
    bad = {k: v for k, v in saved.items() if v is not None and not isinstance(v, str)}
    if bad:
        raise ValueError(f"{model_file}: 'data' holds column names, not {bad}")
    return saved


@app.command("sweep")
@_one_paragraph
@_no_traceback
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
    resume: bool = typer.Option(
        True,
        "--resume/--fresh",
        help="Keep the runs an interrupted sweep of the same file stored in OUT/runs.jsonl "
        "(default), or discard them and start afresh.",
    ),
    quiet: bool = _quiet_option(),
) -> None:
    """Run a robustness sweep from a TOML file; write the table (CSV, Parquet), a summary
    (quantiles per compensator, fraction within the bound), a sensitivity ranking and figures."""
    if bound is not None and not (np.isfinite(bound) and bound > 0):
        _fail(f"--bound must be a finite number > 0 (got {bound})")
    if workers is not None and workers < 1:
        _fail(f"--workers must be >= 1 (got {workers})")
    if n is not None and n < 1:
        _fail(f"--n must be >= 1 (got {n})")
    _check_seed(seed)
    _checked(check_output_folder, out)
    overrides = {"n": n, "seed": seed, "workers": workers, "bound": bound}
    res, the_bound, written = _run_sweep_file(
        config, out, scheduler, overrides, figures, resume, quiet
    )
    metric = res.primary_metric()
    _print_sweep_summary(res, metric, the_bound)
    _print_sensitivity(res, metric)
    e = res.engine
    console.print(
        f"{res.n_runs} runs on {e['engine']} ({e['workers']} worker"
        f"{'s' if e['workers'] != 1 else ''}) in "
        f"{e['wall_seconds']:.1f} s, {e['runs_per_second']:.1f} runs/s"
        + (
            f" ({e['resumed_runs']} more stored by an earlier call)"
            if e.get("resumed_runs")
            else ""
        )
    )
    console.print(f"wrote {len(written)} files to {out}:")
    for path in written:
        console.print(f"  {path}", soft_wrap=True, highlight=False)


def _run_sweep_file(config: Path, out: Path, scheduler, overrides: dict, figures, resume, quiet):
    """Run the sweep of ``config`` (``overrides``: the command line's n, seed, workers and
    bound where given) and save it to ``out``: (result, bound, files written). A bad file
    or a failed sweep is one line on stderr and exit 2; Ctrl-C keeps the finished runs."""
    import hashlib

    from rich.markup import escape

    from ..sweep import SweepError, sweep
    from ..sweep.toml import read_sweep_file

    err = Console(stderr=True)
    runs_file = out / "runs.jsonl"

    def given(key, default):
        return overrides[key] if overrides[key] is not None else default

    try:
        spec = read_sweep_file(config)
        if not resume:
            runs_file.unlink(missing_ok=True)
        res = sweep(
            spec.run,
            spec.design,
            n=given("n", spec.n),
            seed=given("seed", spec.seed),
            engine=scheduler or spec.scheduler or "local",
            workers=given("workers", spec.workers),
            batch_size=spec.batch_size,
            on_error=spec.on_error,
            retries=spec.retries,
            progress=False if quiet else None,  # None: a bar on a terminal only
            checkpoint=runs_file,
            checkpoint_tag=hashlib.sha256(config.read_bytes()).hexdigest()[:16],
        )
        the_bound = given("bound", spec.bound)
        return res, the_bound, res.save(out, bound=the_bound, figures=figures)
    except (ValueError, ConnectionError, SweepError) as exc:
        err.print(f"[red]error:[/red] {escape(str(exc))}", soft_wrap=True, highlight=False)
        raise typer.Exit(2) from None
    except KeyboardInterrupt:
        err.print(
            f"interrupted (Ctrl-C): sweep stopped; its finished runs are kept in {runs_file}: "
            "the same command resumes from them",
            soft_wrap=True,
            highlight=False,
        )
        raise typer.Exit(130) from None


def _print_sweep_summary(res, metric: str, bound) -> None:
    """Median, q95 and max of the primary metric per compensator (and the fraction of runs
    within the bound)."""
    summary = res.summary(bound)
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
    _print_table(table)


def _print_sensitivity(res, metric: str) -> None:
    """The parameters ranked by their influence on ``metric``, per compensator."""
    try:
        sens = res.sensitivity(metrics=metric)
    except ValueError:
        return
    if not len(sens):
        return
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


class _FilesAfterValidate(TyperCommand):
    """``--validate A B C``: every file after one --validate is held out (click would make B
    and C training files, silently)."""

    def parse_args(self, ctx, args):
        out, i, held = [], 0, False
        while i < len(args):
            a = args[i]
            if a == "--":
                out += args[i:]
                break
            if a == "--validate":
                out += args[i : i + 2]
                i += 2
                held = True
                continue
            if a.startswith("--validate="):
                held = True
            elif held and not a.startswith("-"):
                out += ["--validate", a]
                i += 1
                continue
            elif a.startswith("-"):
                held = False
            out.append(a)
            i += 1
        return super().parse_args(ctx, out)


def _cli_note(note: str) -> str:
    """A data-quality note in the command line's words (the Python keyword -> the flag)."""
    return note.replace("consider resample=", "consider --resample RATE (Hz)")


# the long options of `compare`, kept out of its signature
_COMPARE_VALIDATE_OPTION = typer.Option(
    None,
    "--validate",
    help="Held-out data file(s): every file after --validate (put the training files "
    "first). Default: cross-validation.",
)
_COMPARE_REPORT_OPTION = typer.Option(
    None,
    "--report",
    help="Folder for report.html, loops, residuals, comparison.json and winner.json (the "
    "winner's model file).",
)
_COMPARE_MODELS_OPTION = typer.Option(
    None,
    "--models",
    help="Comma-separated candidates, e.g. backlash,bwb,pi,gpi,bwb+poly3 "
    "(default: all of these, CurveAngleModel with a curve angle, and backlash+load, "
    "bwb+load and pi+load with --load); NAME+load (e.g. gpi+load) takes the --load column.",
)
_COMPARE_LOAD_OPTION = typer.Option(
    None,
    "--load",
    help="Measured load column (in a ROS bag /topic:field), for the NAME+load candidates "
    "(the default candidates then include backlash+load, bwb+load and pi+load).",
)
_OBJECTIVE_OPTION = typer.Option(
    "prediction",
    "--objective",
    help="What ranks the candidates: prediction (held-out error) or compensation "
    "(the inverse's error).",
)
_PARSIMONY_OPTION = typer.Option(
    0.0,
    "--parsimony",
    help="A candidate with more parameters wins only by this share of error: the winner is "
    "the one with the fewest parameters within (1 + this) of the best (e.g. 0.05).",
)
_RANGE_MARGIN_OPTION = typer.Option(
    0.1,
    "--range-margin",
    help="A candidate whose held-out prediction leaves the outputs' range by more than "
    "this share of its span is flagged (not excluded: the held-out error decides).",
)


@app.command(cls=_FilesAfterValidate)
@_one_paragraph
@_no_traceback
def compare(
    data: list[Path] = typer.Argument(
        ...,
        help="Training data file(s): CSV/TSV with header, NPY, NPZ, HDF5, Excel, ROS bag "
        "(.bag, .db3, .mcap or a bag folder).",
    ),
    input_col: str = typer.Option(..., "--input", help="Input column; in a ROS bag /topic:field."),
    output_col: str = typer.Option(
        ..., "--output", help="Output column; in a ROS bag /topic:field."
    ),
    time_col: str | None = typer.Option(None, "--time", help=_TIME_HELP),
    time_unit: str = _TIME_UNIT_OPTION,
    curve_angle: str | None = typer.Option(
        None, "--curve-angle", help="Curve-angle column, or a number."
    ),
    validate: list[Path] = _COMPARE_VALIDATE_OPTION,
    holdout: float | None = typer.Option(
        None, "--holdout", help="One split: this fraction at the end of each recording held out."
    ),
    folds: int | None = typer.Option(
        None,
        "--folds",
        help="Cross-validation folds (default: leave one file out; 3 blocks for one file).",
    ),
    models: str | None = _COMPARE_MODELS_OPTION,
    load_col: str | None = _COMPARE_LOAD_OPTION,
    resample: float | None = typer.Option(
        None, "--resample", help="Resample every file to this rate (Hz) first."
    ),
    seed: int = typer.Option(0, "--seed", help="Seed of the global searches."),
    maxiter: int = typer.Option(100, "--maxiter", help="Generations of each global search."),
    report: Path | None = _COMPARE_REPORT_OPTION,
    time_budget: float | None = typer.Option(
        None,
        "--time-budget",
        help="Seconds for the candidates' fits; a candidate that runs out is reported as "
        "out of time.",
    ),
    objective: str = _OBJECTIVE_OPTION,
    range_margin: float = _RANGE_MARGIN_OPTION,
    parsimony: float = _PARSIMONY_OPTION,
    quiet: bool = typer.Option(
        False, "--quiet", "-q", help="No progress bar or per-candidate lines."
    ),
) -> None:
    """Fit candidate models on DATA, rank them on held-out data against y = a x + b; a
    candidate worse than y = a x + b on any held-out part cannot win."""
    _check_choice_options(objective, range_margin, parsimony)
    _check_split_options(holdout, validate, folds)
    _check_seed(seed)
    _note_suspicious(data, validate or [])
    if report is not None:
        _checked(check_output_folder, report, "--report")
    columns = _data_columns(
        time_col, time_unit, input=input_col, output=output_col, curve_angle=curve_angle
    )
    if load_col is not None:
        columns["load"] = load_col
    logs = _checked(_read_logs, data, columns, resample=resample)
    vlogs = _checked(_read_logs, validate, columns, resample=resample) if validate else None
    _checked(_check_comparable, logs + (vlogs or []), output_col)
    split = vlogs if vlogs else (holdout if holdout is not None else "cv")
    options = {
        "folds": folds,
        "seed": seed,
        "maxiter": maxiter,
        "time_budget": time_budget,
        "objective": objective,
        "range_margin": range_margin,
        "parsimony": parsimony,
    }
    result = _checked(_compare_models, logs, models, split, quiet, options)
    _print_comparison(result, output_col)
    _print_parts(result)
    _print_winner(result, holdout is None and not vlogs, bool(vlogs))
    if report is not None:
        _write_comparison(result, report, columns)


def _write_comparison(result, report: Path, columns: dict) -> None:
    """compare --report DIR: the report, and where the winner's model file is. The winner's
    file names the columns it was compared on (as `identify` saves them), so that `predict`
    reads the same input, time, curve angle and load (a Loaded winner needs its load)."""
    from .._util.atomic import write_json

    page = result.report(report)
    record = result.winner.to_dict()
    record["data"] = {k: (None if v is None else str(v)) for k, v in columns.items()}
    write_json(report / "winner.json", record)
    console.print(f"report: {page}", soft_wrap=True)
    console.print(
        f"winner's model file (tendonsheath predict reads it): {report}/winner.json",
        soft_wrap=True,
    )


def _check_choice_options(objective: str, range_margin: float, parsimony: float) -> None:
    """--objective, --range-margin and --parsimony of ``compare``."""
    if objective not in ("prediction", "compensation"):
        _fail(f"--objective must be prediction or compensation (got {objective!r})")
    if not (np.isfinite(range_margin) and range_margin >= 0):
        _fail(f"--range-margin must be a number >= 0 (got {range_margin})")
    if not (np.isfinite(parsimony) and parsimony >= 0):
        _fail(f"--parsimony must be a number >= 0, e.g. 0.05 for 5 % (got {parsimony})")


MAX_PART_COLUMNS = 12  # compare's per-part table: one column per part up to this many


def _print_parts(result) -> None:
    """compare's second table: each candidate's held-out rmse on each held-out part over the
    affine map's there (a * where it exceeds 1: that part keeps it from winning). Printed
    with two parts or more (with one, the ratio is the first table's); a column per part,
    numbered, the parts' names below, so ten held-out files still fit a terminal. Past
    MAX_PART_COLUMNS parts: the best and worst part of each candidate (all of them are in
    comparison.json's val_rmse_parts and Comparison.parts())."""
    from .compare import _ratio_cell

    parts = result.parts()
    labels = parts["labels"]
    if len(labels) < 2:
        return
    table = Table(title="held-out rmse on each held-out part / the affine map's there")
    table.add_column("model", no_wrap=True)
    wide = len(labels) > MAX_PART_COLUMNS
    for head in (
        ["best part", "worst part"] if wide else [f"part {j + 1}" for j in range(len(labels))]
    ):
        table.add_column(head, justify="right")
    for name, ratios, worse in zip(
        parts["models"], parts["ratio_to_affine"], parts["worse_than_affine"], strict=True
    ):
        cells = [_ratio_cell(q, w) for q, w in zip(ratios, worse, strict=True)]
        table.add_row(name, *(_best_and_worst(cells, ratios) if wide else cells))
    _print_table(table)
    names = ", ".join(f"{j + 1} = {label}" for j, label in enumerate(labels))
    console.print(f"parts: {names}", highlight=False, soft_wrap=True)
    if parts["worse_than_affine"].any():
        console.print(
            "*: worse than the affine map on that part: the candidate cannot win",
            highlight=False,
        )


def _best_and_worst(cells: list[str], ratios: np.ndarray) -> list[str]:
    """The best and the worst of a candidate's per-part cells, each with its part's number."""
    if not np.isfinite(ratios).any():
        return ["-", "-"]
    lo, hi = int(np.nanargmin(ratios)), int(np.nanargmax(ratios))
    return [f"{cells[lo]} ({lo + 1})", f"{cells[hi]} ({hi + 1})"]


def _print_winner(result, on_all_data: bool, held_out_files: bool) -> None:
    """The winner line of ``compare``: what it was fitted on."""
    if on_all_data:
        how = "fitted on all the data"
    else:
        how = "fitted on the training files" if held_out_files else "refitted on the whole files"
    console.print(f"winner: {result.winner_name} ({how})")
    if getattr(result, "choice", ""):
        console.print(result.choice, highlight=False, soft_wrap=True)


def _check_split_options(holdout: float | None, validate, folds: int | None) -> None:
    """--holdout, --validate and --folds: one way to hold data out."""
    if holdout is not None and not 0.0 < holdout < 1.0:
        _fail(f"--holdout must be in (0, 1) (got {holdout})")
    if holdout is not None and validate:
        _fail("--holdout and --validate exclude each other")
    if folds is not None and (holdout is not None or validate):
        _fail("--folds is for cross-validation: not with --holdout or --validate")


def _check_comparable(logs: list, output_col: str) -> None:
    """A recording whose output is constant has nothing to compare; print the others' notes."""
    for log in logs:  # before the (long) fitting
        if np.ptp(log.y) == 0.0:
            raise ValueError(
                f"{log.path}: the output {output_col} is constant ({log.y[0]:g}): "
                "there is nothing to compare"
            )
        _print_notes(log)


def _compare_models(logs: list, models: str | None, validate, quiet: bool, options: dict):
    """compare_models on ``logs`` with the candidates named in ``models`` (comma-separated;
    None: the default candidates), printing a line as each candidate is fitted."""
    from .compare import compare_models

    candidates = [m for m in models.split(",") if m.strip()] if models else None

    def done(name, seconds):
        if not quiet:
            console.print(f"  fitted {name} ({seconds:.1f} s)", highlight=False)

    return compare_models(
        logs, models=candidates, validate=validate, on_fit=done, progress=not quiet, **options
    )


def _print_comparison(result, output_col: str) -> None:
    """The comparison table (a failed candidate's reason above it); a winner whose
    validation error is not finite is an error."""
    from .compare import INVERSE_NOTE

    table = Table(title=f"model comparison ({result.mode})")
    longest = max(len(r["model"]) for r in result.table) + 4  # and " (x)"
    table.add_column("model", no_wrap=True, min_width=longest)
    for col in (
        "params",
        f"train rmse ({output_col} units)",
        f"val rmse ({output_col} units)",
        "val nrmse (%)",
        "val rmse / affine's",
        "inverse nrmse (%)",
        "inverse / affine's",
        "wall (s)",
        "CPU (s)",
    ):
        table.add_column(col, justify="right")
    for r in result.table:
        if r.get("error"):
            console.print(f"[yellow]{r['model']}:[/yellow] {r['error']}", highlight=False)
            table.add_row(r["model"], "", "", r.get("status", "failed"), "", "", "", "", "", "")
            continue
        if r.get("excluded"):
            console.print(
                f"[yellow]{r['model']} cannot win:[/yellow] {r['excluded']}", highlight=False
            )
        if r.get("range_flag"):
            console.print(
                f"[yellow]{r['model']} flagged:[/yellow] {r['range_flag']}", highlight=False
            )
        table.add_row(
            r["model"] + (" (x)" if r.get("excluded") else ""),
            str(r["n_params"]),
            f"{r['train_rmse']:.4g}",
            f"{r['val_rmse']:.4g}",
            f"{100 * r['val_nrmse']:.3f}",
            f"{r['ratio_to_affine']:.3f}",
            f"{100 * r.get('inv_nrmse', float('nan')):.3f}",
            f"{r.get('inv_ratio_to_affine', float('nan')):.3f}",
            f"{r['seconds']:.1f}",
            f"{r['cpu_seconds']:.1f}",
        )
    _print_table(table)
    console.print(f"inverse: {INVERSE_NOTE}", highlight=False)
    if any(r.get("excluded") for r in result.table):
        console.print("(x): cannot win (the reason is above)", highlight=False)
    if getattr(result, "rule", ""):
        console.print(f"choice: {result.rule}", highlight=False)
    winner = next((r for r in result.table if r["model"] == result.winner_name), None)
    if winner is not None:
        _check_finite(
            f"winner {result.winner_name}",
            {"val rmse": winner.get("val_rmse"), "val nrmse": winner.get("val_nrmse")},
        )


# a C++ header: a file named .json or .txt would hold C++ that nothing reads as a header
CPP_HEADER_SUFFIXES = {"h", "hpp", "hh", "hxx"}


@app.command("export")
@_one_paragraph
@_no_traceback
def export_command(
    source: Path = typer.Argument(..., help="Model or compensator JSON (from to_json)."),
    cpp: Path = typer.Option(..., "--cpp", help="C++ header to write."),
    namespace: str | None = typer.Option(
        None, "--namespace", help="C++ namespace of the parameters (default: the file's stem)."
    ),
) -> None:
    """Write a saved model or compensator as a C++ header of constexpr parameters, for targets
    with no file system."""
    from .._util.atomic import write_text
    from .export_cpp import cpp_header

    try:
        if not source.is_file():
            raise ValueError(f"file not found: {source}")
        check_output_file(cpp, "--cpp", suffixes=CPP_HEADER_SUFFIXES)
        _refuse_overwriting(cpp, "--cpp", {"source file": source})
        write_text(cpp, cpp_header(source, namespace))
    except ValueError as exc:
        _fail(exc)
    console.print(f"wrote {cpp}", highlight=False)


ros2_app = typer.Typer(
    help="Run on a robot over ROS 2: a compensator node, a simulated drive, a reference, a "
    "recorder (pip install 'tendonsheath\\[ros2]'; see docs/ros2.md).",
    no_args_is_help=True,
)
app.add_typer(ros2_app, name="ros2")

_PARAM_HELP = "A node parameter KEY=VALUE (repeat; see docs/ros2.md), e.g. -p rate=250."
_DURATION_HELP = "Stop after this many seconds (default: run until Ctrl-C)."
_DOMAIN_HELP = "The ROS_DOMAIN_ID (default: the environment's, else 0)."


def _ros2_spin(nodes: list, context, duration: float | None, what: str, finish=None) -> None:
    """Spin until the duration, Ctrl-C or SIGTERM; then ``finish()`` (a recorder's close,
    which destroys its node), the other nodes destroyed and the context shut down."""
    from ..ros2._run import spin

    console.print(f"{what}: running (Ctrl-C stops it)", highlight=False)
    try:
        why = spin(nodes, context, duration)
    finally:
        if finish is not None:
            finish()
        else:
            for node in nodes:
                node.destroy_node()
        if context.ok():
            context.shutdown()
    console.print(f"{what}: stopped ({why})", highlight=False)


@ros2_app.command("compensate")
@_one_paragraph
@_no_traceback
def ros2_compensate(
    file: Path = typer.Argument(..., help="A saved compensator (JSON, from to_json)."),
    joint: list[str] = typer.Option(None, "--joint", help="A joint's name (repeat; in order)."),
    rate: float = typer.Option(200.0, "--rate", help="Control cycles per second (Hz)."),
    param: list[str] = typer.Option(None, "--param", "-p", help=_PARAM_HELP),
    activate: bool = typer.Option(
        True,
        "--activate/--no-activate",
        help="Configure and activate at once, or wait for a "
        "lifecycle manager (its change_state service).",
    ),
    name: str = typer.Option("tendonsheath_compensator", "--name", help="The node's name."),
    domain_id: int | None = typer.Option(None, "--domain-id", help=_DOMAIN_HELP),
    duration: float | None = typer.Option(None, "--duration", help=_DURATION_HELP),
) -> None:
    """Run a saved compensator as a ROS 2 lifecycle node: desired positions in, commands out,
    each cycle's status on /diagnostics."""
    from ..compensate import load
    from ..ros2 import _env
    from ..ros2._run import parsed_parameters
    from ..ros2.compensator_node import PARAMETERS, compensator_node

    _env.ros()
    if not file.is_file():
        _fail(f"file not found: {file}")
    compensator = load(file)
    params = {"rate": rate, **parsed_parameters(param or [], PARAMETERS)}
    if joint:
        params["joints"] = list(joint)
    context = _env.init(domain_id)
    node = compensator_node(compensator, name=name, context=context, parameters=params)
    if activate:
        node.trigger_configure()
        node.trigger_activate()
        if node.live is None:
            _fail("the compensator node failed to configure (see its log above)")
    _ros2_spin([node], context, duration, f"{name} ({type(compensator).__name__})")


@ros2_app.command("plant")
@_one_paragraph
@_no_traceback
def ros2_plant(
    preset: str | None = typer.Option(None, "--preset", help="realistic or ideal."),
    member: int | None = typer.Option(
        None, "--member", help="A population member: ts.presets.random_realistic_plant(SEED)."
    ),
    scenario: Path | None = typer.Option(
        None, "--scenario", help="The plant of a bench scenario file (TOML)."
    ),
    latency: float = typer.Option(0.0, "--latency", help="The tip sensor's latency (s)."),
    noise: float | None = typer.Option(None, "--noise", help="The tip sensor's noise (rad)."),
    seed: int = typer.Option(0, "--seed", help="Seed of the sensors' noise."),
    torque: bool = typer.Option(False, "--torque", help="A torque motor (AdaptiveController)."),
    rate: float = typer.Option(500.0, "--rate", help="Plant steps per second (Hz)."),
    param: list[str] = typer.Option(None, "--param", "-p", help=_PARAM_HELP),
    domain_id: int | None = typer.Option(None, "--domain-id", help=_DOMAIN_HELP),
    duration: float | None = typer.Option(None, "--duration", help=_DURATION_HELP),
) -> None:
    """Run the simulated drive as a ROS 2 node in real time: commands in; the motor encoder,
    the tip sensor (noise, latency) and the load out; route changes from a topic. Default
    plant: --preset realistic."""
    from ..ros2 import _env
    from ..ros2._run import parsed_parameters
    from ..ros2.live_plant import plant_source
    from ..ros2.plant_node import PARAMETERS, plant_node

    _env.ros()
    _check_seed(seed)
    if preset is None and member is None and scenario is None:
        preset = "realistic"
    live = plant_source(
        preset,
        member,
        None if scenario is None else str(scenario),
        latency=latency,
        noise=noise,
        seed=seed,
        torque=torque,
    )
    params = {"rate": rate, **parsed_parameters(param or [], PARAMETERS)}
    context = _env.init(domain_id)
    node = plant_node(live, context=context, parameters=params)
    _ros2_spin([node], context, duration, "tendonsheath_plant")


@ros2_app.command("reference")
@_one_paragraph
@_no_traceback
def ros2_reference(
    amplitude: float = typer.Option(0.3, "--amplitude", help="Amplitude of the sine (rad)."),
    frequency: float = typer.Option(0.5, "--frequency", help="Its frequency (Hz)."),
    offset: float = typer.Option(0.0, "--offset", help="Its offset (rad)."),
    rate: float = typer.Option(200.0, "--rate", help="Messages per second (Hz)."),
    topic: str = typer.Option("desired", "--topic", help="The topic (JointState)."),
    joint: str = typer.Option("joint0", "--joint", help="The joint's name."),
    domain_id: int | None = typer.Option(None, "--domain-id", help=_DOMAIN_HELP),
    duration: float | None = typer.Option(None, "--duration", help=_DURATION_HELP),
) -> None:
    """Publish a sine as the desired position (sensor_msgs/JointState), to try a compensator
    node without a robot's planner."""
    from ..ros2 import _env
    from ..ros2.reference_node import reference_node, sine

    _env.ros()
    signal = sine(amplitude, frequency, offset)
    context = _env.init(domain_id)
    node = reference_node(signal, rate=rate, topic=topic, joint=joint, context=context)
    _ros2_spin([node], context, duration, "tendonsheath_reference")


@ros2_app.command("record")
@_one_paragraph
@_no_traceback
def ros2_record(
    out: Path = typer.Argument(..., help="The bag's folder (new)."),
    topic: list[str] = typer.Option(
        None,
        "--topic",
        help="TOPIC=TYPE, e.g. tip_state=sensor_msgs/msg/JointState (repeat; "
        "default the live loop's topics).",
    ),
    domain_id: int | None = typer.Option(None, "--domain-id", help=_DOMAIN_HELP),
    duration: float | None = typer.Option(None, "--duration", help=_DURATION_HELP),
) -> None:
    """Record topics into a ROS 2 bag (rosbags' writer: no rosbag2 needed) that read_log
    reads back."""
    from ..ros2 import _env
    from ..ros2.recorder import BagRecorder

    _env.ros()
    topics = None
    if topic:
        pairs = [t.partition("=") for t in topic]
        bad = [t for t, (_, sep, kind) in zip(topic, pairs, strict=True) if not (sep and kind)]
        if bad:
            _fail(f"--topic takes TOPIC=TYPE (got {bad[0]!r})")
        topics = {name: kind for name, _, kind in pairs}
    context = _env.init(domain_id)
    recorder = BagRecorder(out, topics, context=context)
    _ros2_spin([recorder.node], context, duration, f"recording {out}", finish=recorder.close)
    counts = ", ".join(f"{k} {v}" for k, v in recorder.counts.items())
    console.print(f"wrote {out} ({counts} messages)", highlight=False)


def main() -> None:
    app()


__all__ = ["MAX_PART_COLUMNS", "app", "main"]

if __name__ == "__main__":
    main()
