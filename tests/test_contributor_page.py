"""docs/contributing.md's "Adding a model", followed with its worked example, the DeadZone: the
page's list of the files a model touches is the whole list (the name occurs in no other source
file: a registration elsewhere fails here), and the model goes through every path a model of
the core's list has: simulate (against the closed form), identify, invert in Python and in C++,
save, load in C++, export, compare."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_export_cpp import _export, compiler  # noqa: E402,F401  (compiler: the fixture)

import tendonsheath as ts  # noqa: E402
from tendonsheath.compensate import InverseFeedforward  # noqa: E402
from tendonsheath.models import Backlash, DeadZone  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
PAGE = ROOT / "docs" / "contributing.md"
# where a model's code lives (tests, docs, benchmarks and examples use it, they do not register it)
SOURCE_FOLDERS = ("include", "src", "python")
SOURCE_SUFFIXES = {".hpp", ".h", ".cpp", ".py", ".txt", ".cmake", ".toml", ".in"}
# the model's names in code: the class and its parameter struct (its ModelPart member,
# dead_zone, is only in the list's line; the words "dead zone" are a plant's too)
NAMES = re.compile(r"\bDeadZone\w*")
T = np.arange(0.0, 4.0, 1e-3)


def files_you_touch(text: str) -> list[str]:
    """The paths of the page's "files you touch: a model" block."""
    found = re.search(r"<!-- files you touch: a model -->\n```text\n(.*?)```", text, flags=re.S)
    assert found, "docs/contributing.md lost its list of the files a model touches"
    return [line.split()[0] for line in found.group(1).splitlines() if line.strip()]


def files_naming(root: Path) -> set[str]:
    """The source files under ``root``'s include/, src/ and python/ that name the model (the
    generated stub _core.pyi aside: the build writes it)."""
    out = set()
    for folder in SOURCE_FOLDERS:
        for path in (root / folder).rglob("*"):
            if path.suffix not in SOURCE_SUFFIXES or not path.is_file():
                continue
            if NAMES.search(path.read_text(encoding="utf-8", errors="replace")):
                out.add(path.relative_to(root).as_posix())
    return out


def test_a_model_touches_at_most_four_files_and_the_page_names_them():
    files = files_you_touch(PAGE.read_text(encoding="utf-8"))
    assert 1 <= len(files) <= 4, files
    assert all((ROOT / f).is_file() for f in files), files


def test_the_model_is_named_in_no_file_the_page_does_not_list():
    assert files_naming(ROOT) == set(files_you_touch(PAGE.read_text(encoding="utf-8")))


def test_the_scan_sees_a_registration_elsewhere(tmp_path):
    # the check above can fail: a file naming the model outside the list is found
    (tmp_path / "python" / "pkg").mkdir(parents=True)
    (tmp_path / "include").mkdir()
    (tmp_path / "src").mkdir()
    (tmp_path / "python" / "pkg" / "registry.py").write_text('KINDS = {"DeadZone": 1}\n')
    (tmp_path / "include" / "other.hpp").write_text("// a dead_zone of a plant\n")
    assert files_naming(tmp_path) == {"python/pkg/registry.py"}


def _closed_form(p: dict, x: np.ndarray) -> np.ndarray:
    right = p["c_r"] * (x - p["d_r"])
    left = p["c_l"] * (x + p["d_l"])
    return np.where(x > p["d_r"], right, np.where(x < -p["d_l"], left, 0.0))


def _random_params(rng) -> dict:
    return {
        "c_r": rng.uniform(0.3, 3.0),
        "c_l": rng.uniform(0.3, 3.0),
        "d_r": rng.uniform(0.0, 0.3),
        "d_l": rng.uniform(0.0, 0.3),
    }


def _input(rng) -> np.ndarray:
    f = rng.uniform(0.3, 1.0)
    return rng.uniform(0.5, 1.0) * np.sin(2 * np.pi * f * T) + 0.1 * np.sin(2 * np.pi * 3.1 * f * T)


def test_simulate_is_the_closed_form():
    rng = np.random.default_rng(21)
    for _ in range(50):
        p = _random_params(rng)
        x = _input(rng)
        np.testing.assert_array_equal(DeadZone(**p).simulate(T, x), _closed_form(p, x))
    with pytest.raises(ValueError, match=r"DeadZone: c_r must be > 0"):
        DeadZone(c_r=0.0)
    with pytest.raises(ValueError, match=r"DeadZone: d_l must be >= 0"):
        DeadZone(d_l=-0.1)


def test_identify_recovers_the_parameters_from_noise_free_data():
    rng = np.random.default_rng(22)
    p = _random_params(rng) | {"d_r": 0.15, "d_l": 0.08}  # edges inside the input's span
    x = _input(rng)
    fit = ts.identify(DeadZone, T, x, DeadZone(**p).simulate(T, x), progress=False, maxiter=60)
    # measured: every parameter to about 1e-13
    for name, value in p.items():
        assert fit.model.params[name] == pytest.approx(value, rel=1e-6, abs=1e-9), name


def test_the_python_inverse_gives_the_desired_output():
    rng = np.random.default_rng(23)
    for _ in range(5):
        model = DeadZone(**_random_params(rng))
        y_d = rng.uniform(0.2, 0.8) * np.sin(2 * np.pi * rng.uniform(0.3, 1.0) * T)
        ff = InverseFeedforward(model, input_range=(-2.0, 2.0))
        u = ff.command(T, y_d)
        # measured 1.1e-16 (the root search's tolerance is far below this)
        assert np.max(np.abs(model.simulate(T, u) - y_d)) < 1e-9


def test_cpp_exported_model_and_loaded_inverse_give_pythons_numbers(tmp_path, compiler):  # noqa: F811
    """The model exported as C++ constants (export --cpp) and its inverse saved by Python and
    loaded in C++ (io/json.hpp, make_model_inverse) give Python's outputs and commands bit for
    bit, in one compiled program."""
    model = DeadZone(c_r=1.3, c_l=0.9, d_r=0.15, d_l=0.08)
    model.to_json(tmp_path / "dz.json")
    _export(tmp_path / "dz.json", tmp_path / "dz.hpp")
    ff = InverseFeedforward(model, input_range=(-2.0, 2.0))
    ff.to_json(tmp_path / "inv.json")
    x = 0.9 * np.sin(2 * np.pi * 0.7 * T[:2000])
    y_d = 0.5 * np.sin(2 * np.pi * 0.4 * T[:2000])
    source = f"""#include <cstdio>
#include <type_traits>
#include <tendonsheath/io/json.hpp>
#include "dz.hpp"
static_assert(std::is_same_v<dz::Model, tendonsheath::DeadZone>);
int main() {{
  auto built = dz::make_model();
  if (!built.ok()) return 1;
  auto& m = built.value();
  auto inverse = tendonsheath::io::load_compensator_json("{tmp_path / "inv.json"}");
  if (inverse.kind() != "InverseFeedforward") return 2;
  double x, y_d, dt;
  while (std::scanf("%lf %lf %lf", &x, &y_d, &dt) == 3)
    std::printf("%.17g %.17g\\n", m.step(x, dt), inverse.step(y_d, dt));
  return 0;
}}
"""
    (tmp_path / "check.cpp").write_text(source)
    exe = tmp_path / "check"
    flags = ["-std=c++17", "-O1", "-Wall", "-Wextra", "-Werror"]
    cmd = [compiler, *flags, f"-I{ROOT / 'include'}", f"-I{tmp_path}", "check.cpp", "-o", "check"]
    build = subprocess.run(cmd, capture_output=True, text=True, cwd=tmp_path)
    assert build.returncode == 0, build.stderr[-3000:]
    dts = np.r_[0.0, np.diff(T[:2000])]
    rows = zip(x.tolist(), y_d.tolist(), dts.tolist(), strict=True)
    stdin = "".join(f"{a!r} {b!r} {c!r}\n" for a, b, c in rows)
    run = subprocess.run([exe], input=stdin, capture_output=True, text=True, check=True)
    out = np.array([[float(v) for v in line.split()] for line in run.stdout.splitlines()])
    np.testing.assert_array_equal(out[:, 0], model.simulate(T[:2000], x))
    np.testing.assert_array_equal(out[:, 1], ff.command(T[:2000], y_d))


# the backlash's fit on the dead zone's data leaves B_l at its bound (and says so)
@pytest.mark.filterwarnings("ignore::tendonsheath.IdentifiabilityWarning")
def test_compare_models_takes_it_and_it_wins_on_its_own_data():
    rng = np.random.default_rng(24)
    x = _input(rng)
    y = DeadZone(c_r=1.2, c_l=0.8, d_r=0.2, d_l=0.1).simulate(T, x)
    # by name too, as the command line gives it
    cmp = ts.compare_models([(T, x, y)], models=["DeadZone", Backlash], validate=0.3, maxiter=30)
    assert cmp.winner_name == "DeadZone"
    # measured held-out rmse about 1e-13 (the data are the model's); a backlash holds its
    # output inside the band, where the dead zone's is 0
    assert cmp.row("DeadZone")["val_rmse"] < 1e-6 < cmp.row("Backlash")["val_rmse"]
