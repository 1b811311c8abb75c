"""Property-based tests (Hypothesis): read_log on random CSV text, identify's input checks
and the model constructors. Each either works or raises the documented error type with a
one-line message; nothing else (a crash, another exception type, a NaN answer) is allowed.
The example counts are kept small so that the module runs in seconds."""

import math
import string

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import tendonsheath as ts
from tendonsheath import io

FAST = settings(
    max_examples=150, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture]
)

# -- read_log on random text -------------------------------------------------------------------

names = st.text(string.ascii_letters + "_ °µ", min_size=1, max_size=6)
cells = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
    st.integers(-(10**6), 10**6).map(str),
    st.sampled_from(["", " ", "nan", "NaN", "-inf", "1e400", "abc", "1,5", '"2.5"', "0x10"]),
    st.text(string.printable, max_size=5),
)


@st.composite
def csv_texts(draw):
    header = draw(st.lists(names, min_size=1, max_size=4))
    delim = draw(st.sampled_from([",", ";", "\t", " "]))
    width = len(header)
    rows = draw(
        st.lists(
            st.lists(cells, min_size=max(1, width - 1), max_size=width + 1), min_size=0, max_size=8
        )
    )
    eol = draw(st.sampled_from(["\n", "\r\n"]))
    lines = [delim.join(header)] + [delim.join(r) for r in rows]
    text = eol.join(lines) + draw(st.sampled_from(["", eol, eol + eol]))
    bom = draw(st.booleans())
    return ("\ufeff" if bom else "") + text, header


@FAST
@given(data=csv_texts(), encoding=st.sampled_from(["utf-8", "cp1252", "utf-16"]))
def test_read_log_on_random_text_works_or_raises_a_one_line_value_error(tmp_path, data, encoding):
    text, header = data
    path = tmp_path / "r.csv"
    try:
        path.write_bytes(text.encode(encoding))
    except UnicodeEncodeError:
        assume(False)
    time = header[0] if len(header) > 1 else None
    try:
        log = io.read_log(path, time=time, input=header[-1], missing="drop")
    except ValueError as exc:
        message = str(exc)
        assert message and "\n" not in message and str(path) in message
        return
    assert np.isfinite(log.x).all() and len(log) >= io.MIN_ROWS
    if log.t is not None:
        assert np.all(np.diff(log.t) > 0)


finite = st.floats(-1e6, 1e6, allow_nan=False, allow_subnormal=False)


@FAST
@given(
    n=st.integers(3, 40),
    dt=st.floats(1e-3, 1e3),
    data=st.data(),
)
def test_written_logs_read_back(tmp_path, n, dt, data):
    x = np.array(data.draw(st.lists(finite, min_size=n, max_size=n)))
    y = np.array(data.draw(st.lists(finite, min_size=n, max_size=n)))
    t = np.arange(n) * dt
    path = io.write_csv(tmp_path / "w.csv", {"time": t, "motor": x, "tip": y})
    log = io.read_log(path, time="time", input="motor", output="tip")
    # write_csv keeps 10 significant digits
    np.testing.assert_allclose(log.t, t, rtol=1e-9, atol=0)
    np.testing.assert_allclose(log.x, x, rtol=1e-9, atol=1e-300)
    np.testing.assert_allclose(log.y, y, rtol=1e-9, atol=1e-300)
    assert log.notes == []


# -- identify's input checks -------------------------------------------------------------------

DEFECTS = ["length", "nan_x", "inf_y", "nan_t", "backwards", "two_d", "short", "empty", "text"]


@st.composite
def bad_recordings(draw):
    n = draw(st.integers(3, 60))
    t = np.arange(n) * 0.01
    x = np.sin(t * 7.0)
    y = 0.8 * x
    defect = draw(st.sampled_from(DEFECTS))
    k = draw(st.integers(0, n - 1))
    if defect == "length":
        y = y[: draw(st.integers(0, n - 1))]
    elif defect == "nan_x":
        x[k] = np.nan
    elif defect == "inf_y":
        y[k] = draw(st.sampled_from([np.inf, -np.inf]))
    elif defect == "nan_t":
        t[k] = np.nan
    elif defect == "backwards":
        k = max(k, 1)
        t[k] = t[k - 1] - draw(st.floats(0.0, 1.0))
    elif defect == "two_d":
        x = np.column_stack([x, x])
    elif defect == "short":
        m = draw(st.integers(0, 2))
        t, x, y = t[:m], x[:m], y[:m]
    elif defect == "empty":
        t, x, y = np.empty(0), np.empty(0), np.empty(0)
    else:
        x = np.array([str(v) for v in x])
        x[k] = "oops"
    return defect, t, x, y


@FAST
@given(case=bad_recordings(), model=st.sampled_from(["Backlash", "BoucWenBacklash"]))
def test_identify_rejects_bad_input_with_a_message(case, model):
    defect, t, x, y = case
    with pytest.raises((ValueError, TypeError)) as info:
        ts.identify(model, t, x, y, maxiter=1, popsize=2, polish=False, progress=False)
    message = str(info.value)
    assert message.strip() and "\n" not in message, (defect, message)


# -- the model constructors --------------------------------------------------------------------

SCALAR_MODELS = {
    "Backlash": ts.models.Backlash,
    "BoucWen": ts.models.BoucWen,
    "BoucWenBacklash": ts.models.BoucWenBacklash,
    "CurveAngleModel": ts.models.CurveAngleModel,
    "FirstOrderLag": ts.models.FirstOrderLag,
    "SecondOrderLag": ts.models.SecondOrderLag,
    "HystereticOscillator": ts.models.HystereticOscillator,
}
numbers = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([0.0, -0.0, -1.0, 1e-300, 1e300, -1e300, 5e-324]),
    st.floats(-10.0, 10.0),
)


def _numeric_defaults(cls) -> dict:
    return {k: v for k, v in cls().params.items() if isinstance(v, int | float)}


@st.composite
def model_params(draw):
    name = draw(st.sampled_from(sorted(SCALAR_MODELS)))
    cls = SCALAR_MODELS[name]
    defaults = _numeric_defaults(cls)
    chosen = draw(st.lists(st.sampled_from(sorted(defaults)), min_size=1, max_size=3, unique=True))
    values = {}
    for key in chosen:
        if isinstance(defaults[key], int) and not isinstance(defaults[key], bool):
            values[key] = draw(st.integers(-(2**40), 2**40))
        else:
            values[key] = draw(numbers)
    return cls, values


@FAST
@given(case=model_params())
def test_model_constructors_accept_or_name_the_bad_parameter(case):
    cls, values = case
    try:
        model = cls(**values)
    except ValueError as exc:
        message = str(exc)
        assert "\n" not in message and any(k in message for k in values), (values, message)
        return
    for k, v in values.items():  # accepted: it is what was asked for
        got = model.params[k]
        assert got == v or (isinstance(v, float) and math.isnan(v) and math.isnan(got))


@FAST
@given(
    cls=st.sampled_from(sorted(SCALAR_MODELS)),
    value=st.one_of(st.none(), st.text(max_size=3), st.lists(st.floats(), max_size=2)),
    data=st.data(),
)
def test_model_constructors_reject_non_numbers_naming_the_parameter(cls, value, data):
    model_cls = SCALAR_MODELS[cls]
    key = data.draw(st.sampled_from(sorted(_numeric_defaults(model_cls))))
    try:
        model = model_cls(**{key: value})
    except (ValueError, TypeError) as exc:
        assert key in str(exc)
        return
    # accepted only as "the default": HysteresisModel treats None so (rho=None has a meaning)
    assert value is None and model.params[key] == model_cls().params[key]
