"""A measured load besides the input, on a real tool: train on three runs, predict the other 47.

    python benchmarks/tool5_load.py [--data ../shared/data/davinci_tool5] [--inputs motor ...]

The data (MRDLab's da Vinci tool 5; ODbL/DbCL; read from its folder at run time, never copied):
50 runs of a 30 deg sine at 0.1-0.5 Hz against ten resistive torque levels. Input: the drive
motor's encoder (``motor``); output: the jaw angle (``jaw``); load: the torque measured at
the jaw (``jaw_torque``, N m, read with ``read_log(..., load="jaw_torque")``).

Training: the runs at 0.1 Hz / 10 %, 0.3 Hz / 50 % and 0.5 Hz / 100 % (issue 25); every model
is identified on those three only, then run over each of the other 47 from its start.

Candidates (each with and without the measured load):

- ``affine``: y = a x + b (least squares); ``affine+load``: y = a x + b + g L;
- ``Backlash``: ``ts.identify(Backlash)``; ``Loaded(Backlash), offset``: the same with the
  tendon's stretch y += gain L (``fixed={"slack": 0, "friction": 0}``);
- ``Loaded(Backlash)``: the stretch and the load's play (slack taken up, friction growing
  with the load; see ``tendonsheath.models.loaded``), identified jointly;
- ``Loaded(Backlash), estimated load``: the same model given, instead of the jaw torque, an
  estimate of it from the motor side (the spindle torque and the motor speed, low-passed
  causally, mapped linearly; the map fitted on the training runs: ``LoadEstimate``).

Figures per held-out run, as the median and the worst over the 47:

- forward: the rmse of the predicted jaw angle (rad);
- inverse: the rmse between the commands the model's inverse sends for the recorded jaw angle
  (low-passed, ``inverse_error.desired_from_record``) under the run's measured load
  (``ts.compensate.LoadCompensated``; ``InverseFeedforward`` without load; the affine maps
  inverted in closed form) and the input that really produced it (rad). The inverse's
  direction-switch smoothing (a share of the peak rate, 0.03-0.4) and the play's switch
  travel (0.25-3 times its zero-load half-width) are chosen per model on the three training
  runs (the settings that best reproduce their inputs);
- the inverse's rmse split: where the recorded jaw moves (``inverse_moving``: its desired
  rate above 15 % of the peak) and where it stands still (``inverse_still``: mostly where the
  motor crosses the play at a reversal; the jaw's record does not say where the motor was
  then, so no inverse of it can);
- the forward error's signed mean per run (``forward_offset`` in ``per_run``), which shows the
  jaw encoder's zero jumping in blocks of runs;
- each as the ratio to the affine map's (without load): the printed and ``target_met`` ratio
  is the median of the model's rmse over the median of the affine map's
  (``median_ratio_to_affine``); the JSON also holds the median and worst per-run ratio.

The chosen model (``Loaded(Backlash)``) was named before any held-out figure was seen: the
physics model of ``tendonsheath.models.loaded`` around the plainest invertible base.

Two things in this data are not the drive's: the jaw encoder is relative (the README says
its zero is arbitrary; the runs' offsets, once the load's is taken off, jump in blocks of
runs, as if it were zeroed anew in each recording session) and the motor
encoder's zero jumps between sessions by about 3 deg (the spindle's absolute encoder shows
it: motor + spindle is constant within a session). Neither can be predicted from the input,
so every figure is given twice:

- ``abs``: the plain rmse;
- ``zero-free``: the rmse with the run's mean error removed (the error of the loop's shape,
  whatever zero the encoders had): a scoring choice made alike for every model.

Inputs (``--inputs``): ``motor`` (raw), ``motor0`` (the motor with its zero taken from the
spindle: x - mean(x + spindle) + the training runs' mean of it; reads the spindle, never the
jaw) and ``spindle`` (the tool's input spindle, negated: the input after the gearbox).

Other bases (``--bases BoucWen PrandtlIshlinskii ...``, default none): ``Loaded(<base>)`` and
``<base>`` are added to the candidates, scored forward only (their inverse figures are NaN);
the chosen model stays ``Loaded(Backlash)``; written to tool5_load_bases.json instead.

Item 5 (rate and load together): the chosen model's per-run ratio to the affine map, as a
table of frequency by load, for the main input; and another split, trained at one rate only
(0.1 Hz at 10, 50 and 100 %), its median ratio per frequency.

Writes benchmarks/results/tool5_load.json; without the data it says so and keeps the old one.
"""

from __future__ import annotations

import argparse
import sys
import time
import warnings
from pathlib import Path

import numpy as np

import tendonsheath as ts
from _common import write_results
from tendonsheath.apps.inverse_error import SMOOTHING_SHARE, desired_from_record
from tendonsheath.compensate import InverseFeedforward, LoadCompensated

DEFAULT = Path(__file__).resolve().parents[2] / "shared" / "data" / "davinci_tool5"
FREQS = (0.1, 0.2, 0.3, 0.4, 0.5)
LOADS = tuple(range(10, 101, 10))
TRAIN = ("f0.10Hz_load010", "f0.30Hz_load050", "f0.50Hz_load100")
INPUTS = ("motor0", "motor", "spindle")
MAIN_INPUT = "motor0"
CHOSEN = "Loaded(Backlash)"
ESTIMATED = "Loaded(Backlash), estimated load"


def run_name(f: float, load: int) -> str:
    return f"f{f:.2f}Hz_load{load:03d}"


def read_runs(data: Path) -> dict[str, ts.io.Log]:
    return {
        run_name(f, p): ts.io.read_log(
            data / f"{run_name(f, p)}.csv",
            time="t",
            input="motor",
            output="jaw",
            load="jaw_torque",
            extra={"spindle": "spindle", "motor_torque": "motor_torque"},
        )
        for f in FREQS
        for p in LOADS
    }


def inputs_of(logs: dict[str, ts.io.Log], kind: str) -> dict[str, np.ndarray]:
    """Every run's input of the given kind (see the module)."""
    if kind == "motor":
        return {k: v.x for k, v in logs.items()}
    if kind == "spindle":
        return {k: -v.extra["spindle"] for k, v in logs.items()}
    zero = {k: float(np.mean(v.x + v.extra["spindle"])) for k, v in logs.items()}
    ref = float(np.mean([zero[k] for k in TRAIN]))
    return {k: v.x - zero[k] + ref for k, v in logs.items()}


class Affine:
    """y = a x + b (+ g L): least squares over the training runs; inverted in closed form."""

    def __init__(self, xs, ys, loads=None):
        cols = [np.concatenate(xs), np.ones(sum(x.size for x in xs))]
        if loads is not None:
            cols.append(np.concatenate(loads))
        self.coef = np.linalg.lstsq(np.column_stack(cols), np.concatenate(ys), rcond=None)[0]
        self.with_load = loads is not None

    def predict(self, t, x, load):
        y = self.coef[0] * x + self.coef[1]
        return y + self.coef[2] * load if self.with_load else y

    def invert(self, t, y_d, load):
        rest = y_d - self.coef[1] - (self.coef[2] * load if self.with_load else 0.0)
        return rest / self.coef[0]


SHARES = (0.03, 0.1, 0.2, 0.4)  # the inverse's direction switch, share of the peak rate
SWITCHES = (0.25, 1.0, 3.0)  # the play's direction switch, times its zero-load half-width


class Identified:
    """A model from ``ts.identify`` (Loaded ones take the load); its inverse's settings are
    chosen on the training runs (``calibrate``), never on a held-out one."""

    def __init__(self, model):
        self.model = model
        self.loaded = isinstance(model, ts.models.Loaded)
        self.share, self.switch = SMOOTHING_SHARE, 0.25

    def calibrate(self, runs) -> None:
        """The (share, switch) whose inverse best reproduces the training runs' inputs."""
        best = None
        for share in SHARES:
            for switch in SWITCHES if self.loaded else (0.25,):
                self.share, self.switch = share, switch
                err = sum(
                    float(
                        np.mean(
                            (self.invert(lg.t, desired_from_record(lg.t, lg.y), lg.load) - x) ** 2
                        )
                    )
                    for lg, x in runs
                )
                if best is None or err < best[0]:
                    best = (err, share, switch)
        assert best is not None
        _, self.share, self.switch = best

    def predict(self, t, x, load):
        if self.loaded:
            return np.asarray(self.model.simulate(t, x, load=load))
        return np.asarray(self.model.simulate(t, x))

    def invert(self, t, y_d, load):
        rate = np.abs(np.diff(y_d)) / np.diff(t)
        smoothing = self.share * float(np.max(rate))
        if self.loaded:
            switch = self.switch * max(float(self.model.radius(0.0)), 1e-6)
            ff = LoadCompensated(self.model, switch=switch, smoothing=smoothing)
            return ff.command(t, y_d, load)
        return np.asarray(InverseFeedforward(self.model, smoothing=smoothing).command(t, y_d))


class LoadEstimate:
    """The jaw torque estimated from the motor side, for a robot without a load sensor:
    L_hat = a m + b tanh(v / 0.05) + c, m the spindle torque and v the motor speed, both
    low-passed causally (2nd-order Butterworth, 2 Hz), a, b, c by least squares on the
    training runs (their measured jaw torque)."""

    def __init__(self, logs, xs, train=TRAIN):
        rows = [self.features(logs[k], xs[k]) for k in train]
        target = np.concatenate([logs[k].load for k in train])
        self.coef = np.linalg.lstsq(np.vstack(rows), target, rcond=None)[0]

    @staticmethod
    def features(log, x):
        from scipy.signal import butter, sosfilt

        sos = butter(2, 2.0, fs=1.0 / float(np.median(np.diff(log.t))), output="sos")
        speed = sosfilt(sos, np.gradient(x, log.t))
        torque = sosfilt(sos, log.extra["motor_torque"])
        return np.column_stack([torque, np.tanh(speed / 0.05), np.ones_like(x)])

    def __call__(self, log, x):
        return self.features(log, x) @ self.coef


class WithEstimate:
    """A model run with the estimated load instead of the measured one."""

    estimated = True

    def __init__(self, model):
        self.model = model

    def predict(self, t, x, load):
        return self.model.predict(t, x, load)

    def invert(self, t, y_d, load):
        return self.model.invert(t, y_d, load)


#: the extra bases' identification options: the hysteretic oscillator is force-driven, its
#: staged path refuses a position input, so its plain search is used
OPTIONS = {"HystereticOscillator": {"strategy": "search"}}


class ForwardOnly:
    """An extra base's model (``--bases``): scored forward only, its inverse NaN."""

    def __init__(self, model):
        self.model = model

    def predict(self, t, x, load):
        if isinstance(self.model, ts.models.Loaded):
            return np.asarray(self.model.simulate(t, x, load=load))
        return np.asarray(self.model.simulate(t, x))

    def invert(self, t, y_d, load):
        return np.full_like(np.asarray(y_d, dtype=float), np.nan)


def extra_bases(recs, loads, bases) -> tuple[dict, dict]:
    """``Loaded(<base>)`` and ``<base>`` for every extra base named, fitted on the training
    runs (forward only), and each fit's seconds."""
    out, seconds = {}, {}
    for base in bases:
        cls = getattr(ts.models, base)
        for name, spec, kw in (
            (f"Loaded({base})", ts.models.Loaded(cls), {"load": loads}),
            (base, cls, {}),
        ):
            start = time.perf_counter()
            kw = {**kw, **OPTIONS.get(base, {})}
            fit = ts.identify(spec, recordings=recs, seed=0, progress=False, **kw)
            seconds[name] = time.perf_counter() - start
            out[name] = ForwardOnly(fit.model)
            print(f"  {name}: train rmse {fit.rmse:.4g} rad ({seconds[name]:.1f} s): {fit.model!r}")
    return out, seconds


def fit_candidates(logs, xs, train=TRAIN, only=None, bases=()) -> tuple[dict, dict]:
    """The candidates (``only``: those named; ``bases``: extra bases, forward only) fitted on
    the training runs, and each fit's seconds."""
    tr = [logs[k] for k in train]
    txs = [xs[k] for k in train]
    recs = [(lg.t, x, lg.y) for lg, x in zip(tr, txs, strict=True)]
    loads = [lg.load for lg in tr]
    out, seconds = {}, {}
    start = time.perf_counter()
    out["affine"] = Affine(txs, [lg.y for lg in tr])
    out["affine+load"] = Affine(txs, [lg.y for lg in tr], loads)
    seconds["affine"] = seconds["affine+load"] = time.perf_counter() - start
    jobs = {
        "Backlash": (ts.models.Backlash, {}),
        "Loaded(Backlash), offset": (
            ts.models.Loaded(ts.models.Backlash),
            {"load": loads, "fixed": {"slack": 0.0, "friction": 0.0}},
        ),
        "Loaded(Backlash)": (ts.models.Loaded(ts.models.Backlash), {"load": loads}),
    }
    for name, (cls, kw) in jobs.items():
        if only is not None and name not in only:
            continue
        start = time.perf_counter()
        fit = ts.identify(cls, recordings=recs, seed=0, progress=False, **kw)
        seconds[name] = time.perf_counter() - start
        out[name] = Identified(fit.model)
        out[name].calibrate(list(zip(tr, txs, strict=True)))
    if bases and only is None:
        extra, extra_seconds = extra_bases(recs, loads, [b for b in bases if b != "Backlash"])
        out.update(extra)
        seconds.update(extra_seconds)
    if only is None:
        out[ESTIMATED] = WithEstimate(out[CHOSEN])
        print(
            f"  {name}: train rmse {fit.rmse:.4g} rad ({seconds[name]:.1f} s), inverse share "
            f"{out[name].share:g}, switch {out[name].switch:g}: {fit.model!r}"
        )
    return out, seconds


# the summarised figures; the inverse split where the recorded jaw moves (its desired rate
# above MOVING_SHARE of the peak) and where it stands still, which is mostly where the motor
# crosses the play at a reversal: no jaw record says where the motor was then
FIGURES = (
    "forward_abs",
    "forward_zero_free",
    "inverse_abs",
    "inverse_zero_free",
    "inverse_moving",
    "inverse_still",
)
MOVING_SHARE = 0.15


def rmse(e: np.ndarray, zero_free: bool) -> float:
    e = e - np.mean(e) if zero_free else e
    return float(np.sqrt(np.mean(e * e)))


def score(logs, xs, models, train=TRAIN) -> dict:
    """Per held-out run and model: forward and inverse rmse, abs and zero-free."""
    estimate = LoadEstimate(logs, xs, train)
    rows = {}
    for key, log in logs.items():
        if key in train:
            continue
        x, load = xs[key], log.load
        desired = desired_from_record(log.t, log.y)
        rate = np.abs(np.gradient(desired, log.t))
        moving = rate > MOVING_SHARE * float(np.max(rate))
        row = {}
        for name, m in models.items():
            used = estimate(log, x) if getattr(m, "estimated", False) else load
            ef = m.predict(log.t, x, used) - log.y
            ei = m.invert(log.t, desired, used) - x
            row[name] = {  # rad, 4 digits (the JSON stays small)
                "forward_abs": float(f"{rmse(ef, False):.4g}"),
                "forward_zero_free": float(f"{rmse(ef, True):.4g}"),
                "inverse_abs": float(f"{rmse(ei, False):.4g}"),
                "inverse_zero_free": float(f"{rmse(ei, True):.4g}"),
                "inverse_moving": float(f"{rmse(ei[moving], False):.4g}"),
                "inverse_still": float(f"{rmse(ei[~moving], False):.4g}"),
                "forward_offset": float(f"{np.mean(ef):.4g}"),
            }
        rows[key] = row
    return rows


def summary(rows: dict, names) -> dict:
    """Median and worst of each figure and of its ratio to the affine map, per model."""
    out = {}
    for name in names:
        entry = {}
        for fig in FIGURES:
            vals = np.array([r[name][fig] for r in rows.values()])
            ratios = np.array([r[name][fig] / r["affine"][fig] for r in rows.values()])
            entry[fig] = {
                "median": float(np.median(vals)),
                "worst": float(np.max(vals)),
                "median_ratio_to_affine": float(np.median(vals))
                / float(np.median([r["affine"][fig] for r in rows.values()])),
                "median_of_ratios": float(np.median(ratios)),
                "worst_ratio": float(np.max(ratios)),
            }
        out[name] = entry
    return out


def grid(rows: dict, name: str, fig: str) -> list[list[float | None]]:
    """Item 5: ratio of ``name`` to the affine map per run, frequency rows by load columns."""
    table = []
    for f in FREQS:
        line: list[float | None] = []
        for p in LOADS:
            r = rows.get(run_name(f, p))
            line.append(None if r is None else r[name][fig] / r["affine"][fig])
        table.append(line)
    return table


def print_summary(kind: str, summ: dict) -> None:
    print(
        f"\n== input {kind}: median (worst) rmse over the 47 held-out runs, mrad; ratio to affine"
    )
    print(f"{'model':34s}" + "".join(f"{h.replace('_', ' '):>22s}" for h in FIGURES))
    for name, e in summ.items():
        cells = ""
        for fig in FIGURES:
            v = e[fig]
            ratio = v["median_ratio_to_affine"]
            cells += f"{1e3 * v['median']:7.1f} ({1e3 * v['worst']:5.1f}) {ratio:5.2f}"
        print(f"{name:34s}{cells}")


ONE_RATE = ("f0.10Hz_load010", "f0.10Hz_load050", "f0.10Hz_load100")


def one_rate_split(logs, xs) -> dict:
    """Item 5, another split: trained at one rate (0.1 Hz, loads 10, 50, 100 %), the chosen
    model's median ratio to the affine map (fitted on the same runs) per frequency."""
    models, _ = fit_candidates(logs, xs, train=ONE_RATE, only=(CHOSEN,))
    rows = score(logs, xs, {k: models[k] for k in ("affine", CHOSEN)}, train=ONE_RATE)
    out = {}
    for fig in ("forward_zero_free", "forward_abs", "inverse_zero_free", "inverse_abs"):
        out[fig] = {
            f"{f:.1f}": float(
                np.median(
                    [
                        r[CHOSEN][fig] / r["affine"][fig]
                        for k, r in rows.items()
                        if k.startswith(f"f{f:.2f}Hz")
                    ]
                )
            )
            for f in FREQS
        }
    print(f"\nitem 5: trained at 0.1 Hz only ({', '.join(ONE_RATE)}): median {CHOSEN} / affine")
    print("  figure              " + "".join(f"{f:>7.1f}" for f in FREQS) + "  Hz")
    for fig, by_f in out.items():
        print(f"  {fig:20s}" + "".join(f"{v:7.2f}" for v in by_f.values()))
    return {"train": list(ONE_RATE), "median_ratio_by_frequency": out}


def print_grid(table, title: str) -> None:
    print(f"\n{title}")
    print("  Hz \\ load %" + "".join(f"{p:>6d}" for p in LOADS))
    for f, line in zip(FREQS, table, strict=True):
        print(f"  {f:9.1f}  " + "".join("  trn " if v is None else f"{v:6.2f}" for v in line))


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--data", type=Path, default=DEFAULT)
    ap.add_argument("--inputs", nargs="+", choices=INPUTS, default=list(INPUTS))
    ap.add_argument("--bases", nargs="*", default=[], help="extra Loaded bases, forward only")
    ap.add_argument("--no-one-rate", action="store_true", help="skip item 5's one-rate split")
    args = ap.parse_args()
    if not all((args.data / f"{k}.csv").is_file() for k in TRAIN):
        print(f"no tool-5 data in {args.data}: benchmarks/results/tool5_load.json kept")
        return 0
    warnings.simplefilter("ignore", ts.IdentifiabilityWarning)
    logs = read_runs(args.data)
    results: dict = {}
    for kind in args.inputs:
        print(f"\n-- input {kind}: fitting on {', '.join(TRAIN)}")
        xs = inputs_of(logs, kind)
        models, seconds = fit_candidates(logs, xs, bases=args.bases)
        rows = score(logs, xs, models)
        summ = summary(rows, list(models))
        print_summary(kind, summ)
        results[kind] = {
            "summary": summ,
            "fit_seconds": seconds,
            "models": {
                k: (m.model.to_dict() if isinstance(m, Identified) else [float(c) for c in m.coef])
                for k, m in models.items()
                if not isinstance(m, WithEstimate | ForwardOnly)
            },
            "inverse_settings": {
                k: {"share": m.share, "switch": m.switch}
                for k, m in models.items()
                if isinstance(m, Identified)
            },
            "per_run": rows,  # held-out run -> model -> figure (rad)
            "grid_forward_zero_free": grid(rows, CHOSEN, "forward_zero_free"),
            "grid_forward_abs": grid(rows, CHOSEN, "forward_abs"),
            "grid_inverse_zero_free": grid(rows, CHOSEN, "inverse_zero_free"),
        }
        if kind == MAIN_INPUT and not args.no_one_rate:
            results[kind]["one_rate"] = one_rate_split(logs, xs)
            for fig in ("forward_zero_free", "forward_abs", "inverse_zero_free"):
                print_grid(
                    results[kind][f"grid_{fig}"],
                    f"item 5: {CHOSEN} / affine, {fig.replace('_', ' ')}, per run (input {kind})",
                )
    main_summary = results.get(MAIN_INPUT, next(iter(results.values())))["summary"][CHOSEN]
    target = {
        fig: main_summary[fig]["median_ratio_to_affine"] <= 0.25
        for fig in ("forward_abs", "forward_zero_free", "inverse_abs", "inverse_zero_free")
    }
    print(
        f"\ntarget (median <= 1/4 of the affine map's) with {CHOSEN}, input {MAIN_INPUT}: {target}"
    )
    path = write_results(
        "tool5_load_bases" if args.bases else "tool5_load",
        {
            "data": "davinci_tool5 (50 runs); train: " + ", ".join(TRAIN),
            "chosen": CHOSEN,
            "main_input": MAIN_INPUT,
            "target": "median rmse <= 1/4 of the affine map's, forward and inverse, with the load",
            "target_met": target,
            "inputs": results,
        },
    )
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
