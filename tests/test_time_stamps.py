"""Time read as it is meant, or refused with the reason (issue 27, step 17 item 4): epoch
seconds written with few or many decimals, integer nanoseconds, ISO-8601 text with and
without UTC offsets, binary float columns, and the time unit (``time_unit=``,
``--time-unit``). Never duplicates or jitter made by rounding."""

import json
import re
from datetime import UTC, datetime, timedelta, timezone

import numpy as np
import pytest
from typer.testing import CliRunner

import tendonsheath as ts
from tendonsheath import io
from tendonsheath.apps.cli import app
from tendonsheath.models import FirstOrderLag

EPOCH_S = 1_700_000_000  # 2023-11-14T22:13:20 UTC
EPOCH_NS = 1_700_000_000_123_456_789


def _csv(path, times, x=None):
    """A CSV with the time cells as given (text) and an input column."""
    times = list(times)
    x = np.sin(np.arange(len(times)) * 0.01) if x is None else x
    lines = ["t,x"] + [f"{c},{float(v)!r}" for c, v in zip(times, x, strict=True)]
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.mark.parametrize("decimals", [3, 6, 9])
def test_epoch_seconds_with_enough_decimals_are_read_exactly(tmp_path, decimals):
    """1 kHz from an epoch second, written with 3, 6 or 9 decimals: the time starts at 0
    and every step is the written one, with no float64 rounding of 1.7e9 (its spacing,
    0.24 us, would show at 6 and 9 decimals)."""
    rng = np.random.default_rng(decimals)
    ns = EPOCH_S * 10**9 + 123_000_000 + np.arange(400) * 1_000_000 + rng.integers(0, 1000, 400)
    cut = 10 ** (9 - decimals)
    written = ns // cut * cut  # the stamps as the file holds them
    cells = [f"{v // 10**9}.{(v % 10**9) // cut:0{decimals}d}" for v in written]
    log = io.read_log(_csv(tmp_path / "e.csv", cells), time="t", input="x")
    np.testing.assert_array_equal(log.t, (written - written[0]) / 1e9)
    assert any("absolute (epoch) stamps" in n and "2023-11-14T22:13:20.123" in n for n in log.notes)


@pytest.mark.parametrize(("decimals", "rate", "what"), [(2, 1000, "2 decimal"), (0, 50, "whole s")])
def test_epoch_seconds_rounded_coarser_than_the_sampling_are_refused(
    tmp_path, decimals, rate, what
):
    """'1700000000.12' at 1 kHz: ten rows share each stamp. Dropping them would keep a
    tenth of the data at the wrong times: refused, naming the column and the resolution."""
    t = EPOCH_S + 0.5 + np.arange(300) / rate
    cells = [f"{v:.{decimals}f}" for v in t]
    with pytest.raises(ValueError, match=r"column 't': \d+ row\(s\) repeat the time") as err:
        io.read_log(_csv(tmp_path / "r.csv", cells), time="t", input="x")
    text = str(err.value)
    assert f"written to {10.0**-decimals:.3g} s ({what}" in text
    mean = float(re.search(r"coarser than the sampling \(([\d.e-]+) s a row", text)[1])
    assert mean == pytest.approx(1 / rate, rel=0.05)  # the rounded span over the rows


def test_a_repeated_row_in_fine_stamps_is_dropped_not_refused(tmp_path):
    """Millisecond stamps at 100 Hz with one row logged twice: a repeat, not rounding."""
    t = [f"{EPOCH_S}.{10 * k:03d}" for k in range(50)]
    t.insert(20, t[19])
    log = io.read_log(_csv(tmp_path / "d.csv", t), time="t", input="x")
    assert log.x.size == 50
    assert any("1 row(s) with a duplicate timestamp dropped" in n for n in log.notes)
    np.testing.assert_allclose(np.diff(log.t), 0.01, rtol=0, atol=1e-12)


def test_rounding_jitter_is_named_as_such(tmp_path):
    """300 Hz written in milliseconds: steps of 3 and 4 ms. The irregularity is the
    rounding's, and the note says so (with the resolution)."""
    t = np.arange(300) / 300.0
    cells = [f"{v:.3f}" for v in t]
    log = io.read_log(_csv(tmp_path / "j.csv", cells), time="t", input="x")
    text = " | ".join(log.notes)
    assert "irregular sampling" in text
    assert "the steps differ by the stamps' resolution (0.001 s, 3 decimal(s) of s)" in text
    fine = io.read_log(_csv(tmp_path / "f.csv", [repr(float(v)) for v in t]), time="t", input="x")
    assert not any("irregular" in n for n in fine.notes)


def test_integer_nanoseconds_are_exact_with_time_unit_ns(tmp_path):
    """1.7e18 ns with nanosecond jitter: float64 has 256 ns steps there; the integer
    difference is taken first, so every stamp is the written one."""
    rng = np.random.default_rng(3)
    ns = EPOCH_NS + np.arange(500) * 1_000_000 + rng.integers(-500, 500, 500)
    path = _csv(tmp_path / "ns.csv", [str(v) for v in ns])
    log = io.read_log(path, time="t", input="x", time_unit="ns")
    expected = (ns - ns[0]) / 1e9
    np.testing.assert_array_equal(log.t, expected)
    naive = (ns.astype(float) - float(ns[0])) / 1e9  # what float parsing would give
    assert np.max(np.abs(naive - expected)) > 1e-8
    with pytest.raises(ValueError, match=r"epoch time in ns\? give time_unit='ns' \(--time-unit"):
        io.read_log(path, time="t", input="x")
    with pytest.raises(ValueError, match=r"epoch time in ns\?"):
        io.read_log(path, time="t", input="x", time_unit="ms")
    with pytest.raises(ValueError, match="time_unit must be one of s, ms, us, ns"):
        io.read_log(path, time="t", input="x", time_unit="sec")


def test_binary_columns_integer_ns_float64_and_float32_epoch_seconds(tmp_path):
    ns = EPOCH_NS + np.arange(200, dtype=np.int64) * 1_000_000 + 7 * (np.arange(200) % 3)
    x = np.cos(np.arange(200) * 0.1)
    np.savez(tmp_path / "a.npz", t=ns, x=x)
    log = io.read_log(tmp_path / "a.npz", time="t", input="x", time_unit="ns")
    np.testing.assert_array_equal(log.t, (ns - ns[0]) / 1e9)
    seconds = EPOCH_S + np.arange(200) / 1000.0
    np.savez(tmp_path / "b.npz", t=seconds, x=x)
    log = io.read_log(tmp_path / "b.npz", time="t", input="x")
    # float64 at 1.7e9 is good to 0.24 us: a margin of 2x its half spacing
    np.testing.assert_allclose(log.t, np.arange(200) / 1000.0, rtol=0, atol=2.4e-7)
    np.savez(tmp_path / "c.npz", t=seconds.astype(np.float32), x=x)
    with pytest.raises(ValueError, match=r"written to 128 s \(float32 numbers\)"):
        io.read_log(tmp_path / "c.npz", time="t", input="x")


def test_time_unit_ms_gives_seconds(tmp_path):
    t_ms = np.arange(100) * 2.5
    path = _csv(tmp_path / "ms.csv", [f"{v:g}" for v in t_ms])
    log = io.read_log(path, time="t", input="x", time_unit="ms")
    np.testing.assert_allclose(log.t, t_ms / 1000.0, rtol=1e-15)
    assert log.sample_time == pytest.approx(0.0025)


def _iso(times: list[datetime], spec="milliseconds") -> list[str]:
    return [d.isoformat(timespec=spec) for d in times]


def test_iso_times_with_offsets_are_utc_across_a_clock_change(tmp_path):
    """Every 0.1 s across the spring-forward change of a +01:00 zone: the wall clock jumps an
    hour, the UTC times do not."""
    start = datetime(2024, 3, 31, 0, 59, 58, tzinfo=UTC)
    utc = [start + timedelta(milliseconds=100 * k) for k in range(40)]
    cet, cest = timezone(timedelta(hours=1)), timezone(timedelta(hours=2))
    local = [d.astimezone(cet if d.hour < 1 else cest) for d in utc]
    log = io.read_log(_csv(tmp_path / "z.csv", _iso(local)), time="t", input="x")
    np.testing.assert_allclose(log.t, 0.1 * np.arange(40), rtol=0, atol=1e-12)
    text = " | ".join(log.notes)
    assert "ISO-8601 times" in text and "2024-03-31T00:59:58.000000000 UTC" in text
    assert "the offset changes within the column" in text
    zulu = [d.strftime("%Y-%m-%dT%H:%M:%S.%fZ") for d in utc]
    log = io.read_log(_csv(tmp_path / "zulu.csv", zulu), time="t", input="x")
    np.testing.assert_allclose(log.t, 0.1 * np.arange(40), rtol=0, atol=1e-12)


def test_iso_times_without_offsets_are_read_as_written(tmp_path):
    start = datetime(2024, 5, 1, 12, 0, 0)
    times = [start + timedelta(microseconds=2500 * k) for k in range(80)]
    cells = [d.isoformat(sep=" ", timespec="microseconds") for d in times]
    log = io.read_log(_csv(tmp_path / "n.csv", cells), time="t", input="x")
    np.testing.assert_allclose(log.t, 0.0025 * np.arange(80), rtol=0, atol=1e-12)
    assert any("no UTC offset: read as written" in n for n in log.notes)


def test_iso_refusals_name_the_row_and_the_reason(tmp_path):
    start = datetime(2024, 5, 1, 12, 0, 0, tzinfo=UTC)
    cells = _iso([start + timedelta(seconds=k) for k in range(10)])
    mixed = [*cells[:5], *(c[:-6] for c in cells[5:])]  # the offset dropped from row 7 on
    with pytest.raises(ValueError, match=r"row 2 has a UTC offset .* row 7 has none"):
        io.read_log(_csv(tmp_path / "m.csv", mixed), time="t", input="x")
    bad = [*cells[:3], "yesterday", *cells[4:]]
    with pytest.raises(ValueError, match=r"column 't', row 5: 'yesterday' is not an ISO-8601"):
        io.read_log(_csv(tmp_path / "b.csv", bad), time="t", input="x")
    with pytest.raises(ValueError, match="ISO-8601 times: time_unit does not apply"):
        io.read_log(_csv(tmp_path / "u.csv", cells), time="t", input="x", time_unit="ms")
    fast = _iso([start + timedelta(milliseconds=10 * k) for k in range(300)], "seconds")
    with pytest.raises(ValueError, match=r"written to 1 s \(whole seconds\)"):
        io.read_log(_csv(tmp_path / "s.csv", fast), time="t", input="x")


def test_excel_datetime_cells_are_iso_times(tmp_path):
    import openpyxl  # a dependency of the package (Excel files)

    book = openpyxl.Workbook()
    sheet = book.active
    sheet.append(["t", "x"])
    start = datetime(2024, 5, 1, 12, 0, 0)
    for k in range(30):
        sheet.append([start + timedelta(milliseconds=20 * k), float(k)])
    book.save(tmp_path / "d.xlsx")
    log = io.read_log(tmp_path / "d.xlsx", time="t", input="x")
    np.testing.assert_allclose(log.t, 0.02 * np.arange(30), rtol=0, atol=1e-6)


def _lag_response(t, tau, w):
    """The closed form of 1 / (tau s + 1) driven by sin(w t) from rest."""
    return (np.sin(w * t) - w * tau * np.cos(w * t) + w * tau * np.exp(-t / tau)) / (
        1 + (w * tau) ** 2
    )


def _fit_percent(output: str) -> float:
    return float(re.search(r"fit (-?[\d.]+) %", output)[1])


def test_cli_predict_reads_the_time_unit_identify_saved(tmp_path):
    """A first-order lag (tau = 50 ms) logged with a millisecond time column. identify
    saves --time-unit ms beside the model; predict reads the time in that unit, so the lag's
    time constant (seconds) meets times in seconds: the closed form is met. Read as seconds
    (--time-unit s), the times are 1000x too long and the prediction misses."""
    t = np.arange(600) * 0.002
    w = 2 * np.pi * 2.0
    data = tmp_path / "ms.csv"
    ts.io.write_csv(data, {"t_ms": t * 1000, "x": np.sin(w * t), "y": _lag_response(t, 0.05, w)})
    runner = CliRunner()
    fitted = tmp_path / "fitted.json"
    cols = ["--input", "x", "--output", "y", "--time", "t_ms", "--time-unit", "ms"]
    args = ["identify", str(data), "-m", "Backlash", *cols, "-o", str(fitted), "--maxiter", "3"]
    result = runner.invoke(app, [*args, "--quiet"])
    assert result.exit_code == 0, result.output
    saved = json.loads(fitted.read_text())["data"]
    assert saved["time_unit"] == "ms" and saved["time"] == "t_ms"
    model = tmp_path / "lag.json"  # the lag itself, with the data identify saved
    record = json.loads(FirstOrderLag(0.05).to_json())
    model.write_text(json.dumps({**record, "data": saved}))
    out = str(tmp_path / "p.csv")
    result = runner.invoke(app, ["predict", str(model), str(data), "-o", out])
    assert result.exit_code == 0, result.output
    assert _fit_percent(result.output) > 99  # the discrete lag vs the closed form: 99.9 %
    result = runner.invoke(app, ["predict", str(model), str(data), "-o", out, "--time-unit", "s"])
    assert result.exit_code == 0, result.output
    assert _fit_percent(result.output) < 50
