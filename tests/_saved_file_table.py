"""The saved kinds (one good file of each) and the defects made from a good file, shared by
test_saved_file_classes.py."""

import copy
import json
import math

from tendonsheath import compensate as C
from tendonsheath import models as M
from tendonsheath.models._bound import model_kinds


def saved_kinds():
    bl = M.Backlash(B_r=0.05, B_l=0.04)
    ms = {
        "Backlash": bl,
        "BoucWen": M.BoucWen(),
        "BoucWenBacklash": M.BoucWenBacklash(),
        "GPI": M.GeneralizedPrandtlIshlinskii(),
        "GPIInverse": M.GeneralizedPrandtlIshlinskiiInverse(),
        "CurveAngleModel": M.CurveAngleModel(),
        "FirstOrderLag": M.FirstOrderLag(),
        "PlantModel": M.PlantModel(),
        "SecondOrderLag": M.SecondOrderLag(),
        "HystereticOscillator": M.HystereticOscillator(),
        "Polynomial": M.Polynomial(degree=2),
        "PI": M.PrandtlIshlinskii(),
        "PIInverse": M.PrandtlIshlinskiiInverse(),
        "Chain": M.Chain(M.BoucWenBacklash(), M.Polynomial(3)),
        "Scaled": M.Scaled(bl, input_offset=0.1, input_scale=1.5, output_gain=-1.2),
        "Loaded": M.Loaded(bl, gain=0.3, slack=0.02, slack_load=0.1, friction=0.05),
    }
    # every other model of the core's list (model_list.hpp), with its defaults
    shown = {type(v).__name__ for v in ms.values()}
    ms |= {k["kind"]: getattr(M, k["kind"])() for k in model_kinds() if k["kind"] not in shown}
    ms["AngleDependent"] = M.AngleDependent(
        "BoucWenBacklash",
        {
            "c_r": [1.0],
            "c_l": [0.95],
            "B_r": [0.0, 0.3],
            "B_l": [0.01, 0.25],
            "rho": [12.0],
            "sigma": [1.0],
            "n": [3.0],
        },
        {"B_r": "tanh", "B_l": "tanh"},
        angle_friction=0.2,
    )
    coupled = M.Coupled([M.Backlash(), M.Backlash(B_r=0.02, B_l=0.03)], [[0, 0.1], [0.25, 0]])
    ff = C.InverseFeedforward(bl, 0.05, (-1.0, 1.0))
    cs = {
        "InverseFeedforward": ff,
        "CurveAngleFeedforward": C.CurveAngleFeedforward(
            friction=0.1, stiffness=1e4, length=1.0, pretension=10.0
        ),
        "ContinuumFeedforward": C.ContinuumFeedforward(),
        "AdaptiveController": C.AdaptiveController.from_model(M.Backlash(1, 1, 0.03, 0.03), 1e-5),
        "EncoderLoop": C.EncoderLoop(ff, kp=1.3, ki=420.0, kd=0.002, max_correction=0.3),
        "TipLoop": C.TipLoop(ff, kp=0.5, ki=40.0, schedule=[(0.5, 0.8), (2.0, 1.5)]),
        "LearnedFeedforward": C.LearnedFeedforward(ff, [0.0, 0.01, 0.02, 0.0], 2.5e-3),
        "LoadCompensated": C.LoadCompensated(ms["Loaded"]),
        "CoupledFeedforward": C.CoupledFeedforward(coupled),
    }
    return ms, coupled, cs


def _leaves(d, path=()):
    """(path, value) of every number/string/bool/null leaf and every container."""
    if isinstance(d, dict):
        for k, v in d.items():
            yield path + (k,), v
            yield from _leaves(v, path + (k,))
    elif isinstance(d, list):
        for i, v in enumerate(d):
            yield path + (i,), v
            yield from _leaves(v, path + (i,))


def _set(d, path, value):
    for p in path[:-1]:
        d = d[p]
    if value is _DEL:
        del d[path[-1]]
    else:
        d[path[-1]] = value


_DEL = object()


def _flip(v):
    if isinstance(v, bool):
        return "yes"
    if isinstance(v, (int, float)):
        return "1.0"
    if isinstance(v, str):
        return 7
    if v is None:
        return "none"
    if isinstance(v, dict):
        return [1]
    if isinstance(v, list):
        return {"a": 1}


def mutations(data):
    """(name, text-or-bytes) malformed versions of the saved dict `data`."""
    text = json.dumps(data)
    out = [
        ("empty", b""),
        ("blank", b"  \n"),
        ("not json", b"model: Backlash\n"),
        ("truncated", text[: len(text) // 2].encode()),
        ("list", json.dumps([data]).encode()),
        ("string", b'"Backlash"'),
        ("number", b"3"),
        ("null", b"null"),
        ("binary", bytes(range(256))),
        ("utf16", text.encode("utf-16")),
        ("utf16le-nobom", text.encode("utf-16-le")),
        ("utf8 bom", ("\ufeff" + text).encode()),
        ("top unknown key", json.dumps({**data, "extra": 1}).encode()),
        ("duplicate key", (text[:-1] + ', "format": "tendonsheath.model"}').encode()),
    ]
    for key in ("format", "version"):
        for bad in ("tendonsheath.other", 2, "1", 1.0, True, None, 0):
            if key == "format" and not isinstance(bad, str) and bad is not None:
                continue
            d = copy.deepcopy(data)
            d[key] = bad
            out.append((f"{key}={bad!r}", json.dumps(d).encode()))
    for path, v in list(_leaves(data)):
        if path[0] in ("format", "version"):
            continue
        name = ".".join(map(str, path))
        d = copy.deepcopy(data)
        if isinstance(path[-1], str):
            _set(d, path, _DEL)
            out.append((f"missing {name}", json.dumps(d).encode()))
        if isinstance(v, dict):
            d = copy.deepcopy(data)
            _set(d, path + ("extra_key",), 1)
            out.append((f"unknown key in {name}", json.dumps(d).encode()))
        d = copy.deepcopy(data)
        _set(d, path, _flip(v))
        out.append((f"wrong type {name}", json.dumps(d).encode()))
        if isinstance(v, (int, float)) and not isinstance(v, bool) or v is None:
            for tag, lit in (
                ("NaN", "NaN"),
                ("inf", "Infinity"),
                ("overflow", "1e999"),
                ("huge", "1e300"),
                ("negative", "-1.5"),
                ("zero", "0"),
                ("bigint", "9" * 400),
            ):
                d = copy.deepcopy(data)
                _set(d, path, "@@@")
                out.append((f"{tag} {name}", json.dumps(d).replace('"@@@"', lit).encode()))
    return out


def same(a, b):
    if isinstance(a, bool) or isinstance(b, bool):
        return type(a) is type(b) and a == b
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        return float(a) == float(b) or (math.isnan(a) and math.isnan(b))
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(same(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b, strict=True))
    return a == b


def verdict(call, path, content, original):
    try:
        obj = call(path)
    except (ValueError, TypeError) as e:
        m = str(e)
        if "\n" in m:
            return "MULTILINE", m
        if str(path) not in m:
            return "NOPATH", m
        return "error", m
    except Exception as e:
        return "CRASH", f"{type(e).__name__}: {e}"
    try:
        got = obj.to_dict()
    except Exception as e:
        return "CRASH", f"to_dict {type(e).__name__}: {e}"
    try:
        meant = json.loads(content.decode("utf-8-sig")) if isinstance(content, bytes) else content
    except Exception:
        meant = original
    if same(got, meant):
        return "faithful", ""
    return "SILENT", json.dumps(got)[:300]
