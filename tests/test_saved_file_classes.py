"""Every kind of file the library saves (each model class, a Coupled model, each compensator),
read back through every loader after one defect generated from the good file (empty, not JSON,
another top-level type, a key missing or unknown, a value of the wrong type, NaN, inf, 1e999,
1e300, -1.5, 0, a 400-digit integer, another format or version, binary bytes, UTF-16): a one-line
ValueError naming the file, or the object the file says, value for value. A missing key loads
only where it has a documented default (docs/bad-inputs.md, "Saved files read back")."""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

import pytest
from typer.testing import CliRunner

sys.path.insert(0, str(Path(__file__).resolve().parent))
import _saved_file_table as table  # noqa: E402

from tendonsheath import compensate, models  # noqa: E402
from tendonsheath.apps.cli import app  # noqa: E402
from tendonsheath.apps.export_cpp import cpp_header  # noqa: E402

# keys whose absence has a documented meaning: an option, a limit (unbounded, as null), a law
# (constant), Scaled's map (identity) and settings added after version 1 was first written
DEFAULTED = {
    "options", "max_step", "max_substeps", "elements", "substeps", "input_interpolation",
    "lookahead", "odd", "base_options", "play", "input_range", "range_margin", "filter_hz",
    "min", "max", "max_rate", "input_offset", "input_scale", "output_offset", "output_gain",
    "c_r", "c_l", "rho", "sigma", "n",
}  # fmt: skip
MODELS, COUPLED, COMPENSATORS = table.saved_kinds()
LOADERS = {
    "model": models.load_model,
    "coupled": models.Coupled.load,
    "compensator": compensate.load,
}
KINDS = [("model", k, m) for k, m in MODELS.items()]
KINDS += [("coupled", "Coupled", COUPLED)]
KINDS += [("compensator", k, c) for k, c in COMPENSATORS.items()]


def _allowed_default(case: str) -> bool:
    if not case.startswith("missing "):
        return False
    path = case.removeprefix("missing ").split(".")
    return path[-1] in DEFAULTED and (path[-1] not in ("c_r", "c_l", "rho", "sigma", "n")
                                      or "laws" in path)  # fmt: skip


@pytest.mark.parametrize(("kind", "name", "obj"), KINDS, ids=[k[1] for k in KINDS])
def test_every_defect_of_every_saved_kind(tmp_path, kind, name, obj):
    load = LOADERS[kind]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        cases = table.mutations(obj.to_dict())
        for i, (case, content) in enumerate(cases):
            path = tmp_path / f"{i}.json"
            path.write_bytes(content)
            verdict, message = table.verdict(load, path, content, obj.to_dict())
            if verdict == "SILENT" and _allowed_default(case):
                continue  # the key's documented default, which to_dict writes back
            assert verdict in ("error", "faithful"), (case, verdict, message)
    assert len(cases) > 20


def _file_level(obj) -> list[tuple[str, bytes]]:
    return [c for c in table.mutations(obj.to_dict()) if " " not in c[0] or "utf" in c[0]]


OTHER_KIND = [
    (models.load_model, COMPENSATORS["InverseFeedforward"], "not a tendonsheath model file"),
    (models.load_model, COUPLED, "not a tendonsheath model file"),
    (compensate.load, MODELS["Backlash"], "not a tendonsheath compensator file"),
    (models.Coupled.load, MODELS["Backlash"], "not a 'tendonsheath.coupled_model' file"),
    (compensate.InverseFeedforward.load, COMPENSATORS["EncoderLoop"], "holds a EncoderLoop"),
]


@pytest.mark.parametrize(("load", "obj", "words"), OTHER_KIND)
def test_a_file_of_another_kind_names_what_it_holds(tmp_path, load, obj, words):
    path = tmp_path / "other.json"
    path.write_text(obj.to_json())
    with pytest.raises((ValueError, TypeError), match=words) as info:
        load(path)
    assert "\n" not in str(info.value)


@pytest.mark.parametrize("load", [*LOADERS.values(), cpp_header])
def test_a_folder_or_a_missing_path(tmp_path, load):
    for path in (tmp_path, tmp_path / "missing.json"):
        with pytest.raises(ValueError) as info:
            load(path)
        assert str(path) in str(info.value) and "\n" not in str(info.value)


@pytest.fixture(scope="module")
def data(tmp_path_factory) -> Path:
    import numpy as np

    from tendonsheath import io

    d = tmp_path_factory.mktemp("data")
    t = np.arange(50) * 0.01
    io.write_csv(d / "data.csv", {"t": t, "x": np.sin(t), "y": np.sin(t)})
    return d


@pytest.mark.parametrize("obj", [MODELS["Backlash"], MODELS["PI"], COMPENSATORS["LoadCompensated"]])
def test_the_commands_that_read_a_saved_file(tmp_path, data, obj):
    """predict (a model) and export (both): one line "error: FILE: ...", exit 2."""
    runner = CliRunner()
    commands = [["export", "@", "--cpp", str(tmp_path / "o.hpp")]]
    if isinstance(obj, models.HysteresisModel):
        csv = str(data / "data.csv")
        commands.append(["predict", "@", csv, "--input", "x", "-o", str(tmp_path / "p.csv")])
    for i, (case, content) in enumerate(_file_level(obj)):
        path = tmp_path / f"saved_{i}.json"
        path.write_bytes(content)
        for command in commands:
            result = runner.invoke(app, [str(path) if a == "@" else a for a in command])
            out = result.output.strip()
            if result.exit_code == 0:
                continue  # a good file (UTF-8 with a byte-order mark, UTF-16)
            assert result.exit_code == 2 and "\n" not in out, (case, command[0], out)
            assert out.startswith(f"error: {path}"), (case, command[0], out)
