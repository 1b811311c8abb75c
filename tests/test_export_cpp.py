"""`tendonsheath export FILE --cpp OUT.hpp`: the header compiles, its parameters are constexpr,
and the core built from them steps exactly like the same file loaded with io/json.hpp (which
test_cpp_example_12 ties to Python) or holds Python's numbers bit for bit (models)."""

import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from tendonsheath.apps.cli import app
from tendonsheath.compensate import (
    ContinuumFeedforward,
    CurveAngleFeedforward,
    InverseFeedforward,
)
from tendonsheath.models import Backlash, BoucWenBacklash, Polynomial, PrandtlIshlinskii, Scaled

ROOT = Path(__file__).resolve().parents[1]
PI = PrandtlIshlinskii(thresholds=[0.0, 0.1, 0.25], weights=[0.9, 0.3, 0.15])

# namespace -> (object, C++ expression of the compensator built from the constexpr params)
COMPENSATORS = {
    "inv_backlash": (
        InverseFeedforward(Backlash(c_r=0.93, B_r=0.11, B_l=0.07), 0.04, (-2.0, 2.0, 40.0)),
        "tendonsheath::BacklashInverseFeedforward c(P::params);",
    ),
    "inv_bw": (
        InverseFeedforward(BoucWenBacklash(c_l=1.2, B_l=0.2, rho=8.0), 0.02),
        "tendonsheath::BacklashInverseFeedforward c(P::params);",
    ),
    "inv_pi": (
        InverseFeedforward(PI, limits={"max_rate": 25.0}),
        "tendonsheath::PrandtlIshlinskiiFeedforward c({{std::begin(P::thresholds), "
        "std::end(P::thresholds)}, {std::begin(P::weights), std::end(P::weights)}}, P::limits);",
    ),
    "curve_angle": (
        CurveAngleFeedforward(0.11, 1 / 3e-4, 1.0, 12.0, load_stiffness=40.0, curve_angle=2.2),
        "tendonsheath::CurveAngleFeedforward c(P::params);",
    ),
    "continuum": (
        ContinuumFeedforward(curve_angle=2.0, mode="published", limits=(-3.0, 3.0)),
        "tendonsheath::ContinuumFeedforward c(P::params);",
    ),
}
SCALED = InverseFeedforward(
    Scaled(Backlash(B_r=0.05), input_offset=0.2, input_scale=1.7, output_gain=-0.9), 0.05
)


def _export(path: Path, out: Path) -> None:
    result = CliRunner().invoke(app, ["export", str(path), "--cpp", str(out)])
    assert result.exit_code == 0, result.output


def _compensator_check(ns: str, build: str, json_path: Path, scaled: bool = False) -> str:
    command = (
        "P::input_offset + P::input_scale * c.step((y - P::output_offset) / P::output_gain, dt)"
        if scaled
        else "c.step(y, dt)"
    )
    return f"""
  {{
    namespace P = {ns};
    {build}
    auto loaded = tendonsheath::io::load_compensator_json("{json_path}");
    for (int k = 0; k < 3000; ++k) {{
      const double y = 0.9 * std::sin(0.004 * k) + 0.05 * std::sin(0.07 * k), dt = 1e-3;
      if ({command} != loaded.step(y, dt)) {{ std::printf("{ns} differs at %d\\n", k); return 1; }}
    }}
  }}"""


@pytest.fixture(scope="module")
def compiler():
    cxx = shutil.which("c++") or shutil.which("g++")
    if cxx is None or not Path("/usr/include/nlohmann/json.hpp").is_file():
        pytest.fail("needs a C++ compiler and nlohmann/json: run `make test-cpp` first")
    return cxx


def test_exported_headers_compile_and_match_the_json_loader(tmp_path, compiler):
    includes, checks = [], []
    items = {**{k: v for k, v in COMPENSATORS.items()}, "scaled": (SCALED, None)}
    for ns, (ff, build) in items.items():
        ff.to_json(tmp_path / f"{ns}.json")
        _export(tmp_path / f"{ns}.json", tmp_path / f"{ns}.hpp")
        includes.append(f'#include "{ns}.hpp"')
        if ns == "scaled":
            build = "tendonsheath::BacklashInverseFeedforward c(P::params);"
        checks.append(_compensator_check(ns, build, tmp_path / f"{ns}.json", ns == "scaled"))
    constexpr = (
        "static_assert(inv_backlash::params.smoothing == 0.04 && "
        "continuum::params.limits.max == 3.0);"
    )
    source = (
        "#include <cmath>\n#include <cstdio>\n#include <iterator>\n"
        "#include <tendonsheath/io/json.hpp>\n" + "\n".join(includes) + f"\n{constexpr}\n"
        "int main() {" + "".join(checks) + '\n  std::printf("ok\\n");\n  return 0;\n}\n'
    )
    (tmp_path / "check.cpp").write_text(source)
    exe = tmp_path / "check"
    build = subprocess.run(
        [
            compiler,
            "-std=c++17",
            "-O1",
            "-Wall",
            "-Wextra",
            "-Werror",
            f"-I{ROOT / 'include'}",
            f"-I{tmp_path}",
            str(tmp_path / "check.cpp"),
            "-o",
            str(exe),
        ],
        capture_output=True,
        text=True,
    )
    assert build.returncode == 0, build.stderr[-3000:]
    run = subprocess.run([exe], capture_output=True, text=True)
    assert run.returncode == 0 and run.stdout == "ok\n", run.stdout


def test_exported_models_hold_pythons_numbers_bit_for_bit(tmp_path, compiler):
    models = {
        "bl": Backlash(c_r=0.97, c_l=1.03, B_r=0.1234567891234, B_l=1e-5),
        "bw": BoucWenBacklash(rho=17.5, sigma=0.75, n=2.0, max_substeps=64),
        "pi": PI,
    }
    prints = []
    for ns, model in models.items():
        model.to_json(tmp_path / f"{ns}.json")
        _export(tmp_path / f"{ns}.json", tmp_path / f"{ns}.hpp")
        names = model.param_names + model.option_names
        if ns == "pi":
            prints += [
                f'for (double v : pi::{k}) std::printf("pi {k} %.17g\\n", v);' for k in names
            ]
        else:
            prints += [
                f'std::printf("{ns} {k} %.17g\\n", double({ns}::params.{k}));' for k in names
            ]
    source = "#include <cstdio>\n#include <type_traits>\n"
    source += "".join(f'#include "{ns}.hpp"\n' for ns in models)
    # each header names the class its parameters build, and builds it
    classes = {"bl": "Backlash", "bw": "BoucWenBacklash", "pi": "PrandtlIshlinskii"}
    source += "".join(
        f"static_assert(std::is_same_v<{ns}::Model, tendonsheath::{c}>);\n"
        for ns, c in classes.items()
    )
    built = " || ".join(f"!{ns}::make_model().ok()" for ns in models)
    source += f"int main() {{\n  if ({built}) return 1;\n" + "\n".join(prints) + "\n}\n"
    (tmp_path / "models.cpp").write_text(source)
    exe = tmp_path / "models"
    cmd = [
        compiler,
        "-std=c++17",
        f"-I{ROOT / 'include'}",
        f"-I{tmp_path}",
        str(tmp_path / "models.cpp"),
        "-o",
        str(exe),
    ]
    assert subprocess.run(cmd, capture_output=True).returncode == 0
    seen: dict = {}
    for line in subprocess.run([exe], capture_output=True, text=True, check=True).stdout.split(
        "\n"
    )[:-1]:
        ns, key, value = line.split()
        seen.setdefault((ns, key), []).append(float(value))
    for ns, model in models.items():
        values = {**model.params, **model.options}
        for key, value in values.items():
            assert np.array_equal(seen[(ns, key)], np.ravel(value)), (ns, key)


def test_unsupported_models_are_one_line_errors(tmp_path):
    Polynomial(degree=3).to_json(tmp_path / "poly.json")
    result = CliRunner().invoke(
        app, ["export", str(tmp_path / "poly.json"), "--cpp", str(tmp_path / "p.hpp")]
    )
    assert result.exit_code == 2
    assert "export --cpp writes Backlash" in result.output and "Traceback" not in result.output
    result = CliRunner().invoke(
        app, ["export", str(tmp_path / "none.json"), "--cpp", str(tmp_path / "p.hpp")]
    )
    assert result.exit_code == 2 and "file not found" in result.output


# namespace -> (the class its header names, a field to spoil): the header builds it with
# make_compensator() without exceptions too
WITHOUT_EXCEPTIONS = {
    "inv_backlash": ("BacklashInverseFeedforward", "smoothing"),
    "inv_bw": ("BacklashInverseFeedforward", "smoothing"),
    "inv_pi": ("PrandtlIshlinskiiFeedforward", None),
    "curve_angle": ("CurveAngleFeedforward", "smoothing"),
    "continuum": ("ContinuumFeedforward", "smoothing"),
}


def _no_exceptions_check(ns: str, cpp_class: str, field: str | None) -> str:
    spoiled = (
        f"""
    auto bad = {ns}::params;
    bad.{field} = -1.0;
    const auto refused = tendonsheath::make<{ns}::Compensator>(bad);
    std::printf("%s\\n", refused.ok() ? "ok" : refused.error().c_str());"""
        if field
        else ""
    )
    return f"""
  {{
    static_assert(std::is_same_v<{ns}::Compensator, tendonsheath::{cpp_class}>);
    auto built = {ns}::make_compensator();
    if (!built.ok()) return 1;
    {ns}::Compensator& c = built.value();
    for (std::size_t k = 0; k < n; ++k)
      std::printf("%.17g\\n", c.step(y[k], k == 0 ? 0.0 : t[k] - t[k - 1]));{spoiled}
  }}"""


def test_exported_headers_build_without_exceptions(tmp_path, compiler):
    """Each exported compensator header names its class and builds it with make_compensator()
    under g++ -fno-exceptions: Python's commands to 1e-12 on a 1 kHz trajectory, and a bad
    parameter comes back as the error message, not a throw (docs/cpp-without-exceptions.md)."""
    t = np.arange(0.0, 2.0, 1e-3)
    y_d = 0.8 * np.sin(2 * np.pi * 0.5 * t) + 0.1 * np.sin(2 * np.pi * 3.1 * t)
    rows = ",\n".join(f"{{{a!r}, {b!r}}}" for a, b in zip(t.tolist(), y_d.tolist(), strict=True))
    source = "#include <cstdio>\n#include <type_traits>\n"
    checks = []
    for ns, (cpp_class, field) in WITHOUT_EXCEPTIONS.items():
        COMPENSATORS[ns][0].to_json(tmp_path / f"{ns}.json")
        _export(tmp_path / f"{ns}.json", tmp_path / f"{ns}.hpp")
        source += f'#include "{ns}.hpp"\n'
        checks.append(_no_exceptions_check(ns, cpp_class, field))
    source += f"const double trajectory[][2] = {{\n{rows}}};\n"
    source += (
        "int main() {\n  const std::size_t n = sizeof trajectory / sizeof trajectory[0];\n"
        "  double t[sizeof trajectory / sizeof trajectory[0]], y[sizeof t / sizeof t[0]];\n"
        "  for (std::size_t k = 0; k < n; ++k) t[k] = trajectory[k][0], y[k] = trajectory[k][1];"
        + "".join(checks)
        + "\n  return 0;\n}\n"
    )
    (tmp_path / "noexc.cpp").write_text(source)
    exe = tmp_path / "noexc"
    flags = ["-std=c++17", "-O1", "-fno-exceptions", "-Wall", "-Wextra", "-Werror"]
    include = [f"-I{ROOT / 'include'}", f"-I{tmp_path}"]
    build = subprocess.run(
        [compiler, *flags, *include, str(tmp_path / "noexc.cpp"), "-o", str(exe)],
        capture_output=True,
        text=True,
    )
    assert build.returncode == 0, build.stderr[-3000:]
    lines = subprocess.run([exe], capture_output=True, text=True, check=True).stdout.split("\n")
    at = 0
    for ns, (cpp_class, field) in WITHOUT_EXCEPTIONS.items():
        cpp = np.array([float(v) for v in lines[at : at + t.size]])
        at += t.size
        python = COMPENSATORS[ns][0].command(t, y_d)
        assert np.ptp(python) > 0.5, ns  # the trajectory exercises the compensator
        np.testing.assert_allclose(cpp, python, rtol=0, atol=1e-12, err_msg=ns)
        if field:
            assert lines[at] == f"{cpp_class}: {field} must be > 0 (got -1)", lines[at]
            at += 1
    assert lines[at:] == [""]
