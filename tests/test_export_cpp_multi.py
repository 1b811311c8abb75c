"""`tendonsheath export FILE --cpp OUT.hpp` of a LoadCompensated and a CoupledFeedforward: the
headers build the core's own classes from constants (no JSON) with make_compensator() under
g++ -fno-exceptions, and their step, the class's own (load as third argument; J angles in, J
commands out), gives Python's commands over random models, loads with dropouts and 2 or 3
joints. One program holds every case of both classes (one compile)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_cpp_multi_input_json import DTS, T, _coupled, _desired, _load_compensated  # noqa: E402
from test_export_cpp import _export, compiler  # noqa: E402,F401  (compiler: the fixture)
from test_inverse_every_model import EXACT, _angle_backlash  # noqa: E402

from tendonsheath.apps.export_cpp import cpp_header  # noqa: E402
from tendonsheath.compensate import CoupledFeedforward, InverseFeedforward  # noqa: E402
from tendonsheath.models import Backlash, Chain, Coupled, FirstOrderLag, Polynomial  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
LC_CASES, CF_CASES = range(8), range(6)  # every base, range and limit setting of their makers


def _extra_coupled(k: int) -> CoupledFeedforward:
    """Joints whose inverses the single-input export does not write: root-finding inverses (a
    GPI, a PlantModel, a BoucWenBacklash followed by a polynomial, a BoucWen) and a Hammerstein
    chain (a lag's inverse before a Backlash's), with their nested and integer fields."""
    rng = np.random.default_rng(500 + k)
    if k == 0:
        models = [EXACT[name](rng) for name in ("GeneralizedPrandtlIshlinskii", "PlantModel")]
        models.append(EXACT["BoucWenBacklash+poly"](rng))
    else:
        lag = Chain(Backlash(B_r=0.04, B_l=0.03), FirstOrderLag(time_constant=0.02))
        models = [EXACT["BoucWen"](rng), lag]
    c = rng.uniform(-0.2, 0.2, (len(models), len(models)))
    np.fill_diagonal(c, 0.0)
    return CoupledFeedforward(Coupled(models, c), smoothing=0.02, input_range=(-1.5, 1.5))


def _lc_case(ns: str) -> str:
    return f"""
  {{
    static_assert(std::is_same_v<{ns}::Compensator,
                                 tendonsheath::LoadCompensated<tendonsheath::ModelInverse>>);
    auto built = {ns}::make_compensator();
    if (!built.ok()) return 1;
    {ns}::Compensator& c = built.value();
    for (std::size_t k = 0; k < n; ++k) {{
      double y, dt, load;
      if (std::scanf("%lf %lf %lf", &y, &dt, &load) != 3) return 2;
      std::printf("%.17g\\n", c.step(y, dt, load));
    }}
  }}"""


def _cf_case(ns: str) -> str:
    return f"""
  {{
    static_assert(std::is_same_v<{ns}::Compensator, tendonsheath::CoupledFeedforward>);
    auto built = {ns}::make_compensator();
    if (!built.ok()) return 1;
    {ns}::Compensator& c = built.value();
    double y[{ns}::joints], u[{ns}::joints];
    for (std::size_t k = 0; k < n; ++k) {{
      double dt;
      if (std::scanf("%lf", &dt) != 1) return 2;
      for (double& v : y) if (std::scanf("%lf", &v) != 1) return 2;
      c.step(y, u, dt);
      for (double v : u) std::printf("%.17g ", v);
      std::printf("\\n");
    }}
  }}"""


# a bad constant comes back from make() as the message, not a throw
SPOILED = """
  {
    auto terms = lc0::terms;
    terms.switch_travel = -1.0;
    const auto bad = tendonsheath::make<lc0::Compensator>(lc0::base_inverse(), terms);
    std::printf("%s\\n", bad.ok() ? "ok" : bad.error().c_str());
    std::vector<double> coupling(std::begin(cf0::coupling), std::end(cf0::coupling));
    coupling[0] = 0.5;
    const auto refused = tendonsheath::make<cf0::Compensator>(cf0::joint_inverses(), coupling);
    std::printf("%s\\n", refused.ok() ? "ok" : refused.error().c_str());
  }"""


def _number(v: float) -> str:
    return repr(float(v))


def _inputs(ns: str, ff, rng) -> tuple[list[str], np.ndarray, str]:
    """(stdin lines, Python's streamed commands, the C++ block) of one case: a LoadCompensated
    under a load with dropouts, or coupled joints whose desired angles have dropouts."""
    ff.reset()
    if ns.startswith("lc"):
        y_d = _desired(rng)
        load = 0.3 * np.sin(2 * np.pi * rng.uniform(0.2, 1.0) * T + 1.0)
        load[rng.integers(0, T.size, 5)] = np.nan  # lost load samples: the last one held
        rows = list(zip(y_d, DTS, load, strict=True))
        python = np.array([ff.step(a, dt, b) for a, dt, b in rows])
        return [" ".join(map(_number, row)) + "\n" for row in rows], python, _lc_case(ns)
    y_d = _desired(rng, ff.model.joints)
    y_d[rng.integers(0, T.size, 4), rng.integers(0, ff.model.joints, 4)] = np.nan
    python = np.array([ff.step(y, dt) for y, dt in zip(y_d, DTS, strict=True)])
    lines = [" ".join(map(_number, [dt, *y])) + "\n" for y, dt in zip(y_d, DTS, strict=True)]
    return lines, python, _cf_case(ns)


def run_exported(cases: dict, folder: Path, cxx: str, extra: str = "") -> tuple:
    """Export every case (namespace "lc..." a LoadCompensated, "cf..." a CoupledFeedforward)
    into ``folder``, build one program of them all (g++ -fno-exceptions; ``extra``: C++ run
    after them) and run it over random inputs: ({ns: Python's commands}, {ns: C++'s}, the
    lines ``extra`` printed). benchmarks/cpp_multi_input_json.py --export runs it too."""
    source, checks, stdin, expected = "#include <cstdio>\n#include <type_traits>\n", [], [], {}
    for index, (ns, ff) in enumerate(cases.items()):
        ff.to_json(folder / f"{ns}.json")
        _export(folder / f"{ns}.json", folder / f"{ns}.hpp")
        source += f'#include "{ns}.hpp"\n'
        lines, expected[ns], check = _inputs(ns, ff, np.random.default_rng(300 + index))
        stdin += lines
        checks.append(check)
    source += (
        f"int main() {{\n  const std::size_t n = {T.size};" + "".join(checks) + extra + "\n}\n"
    )
    (folder / "multi.cpp").write_text(source)
    exe = folder / "multi"
    # -O0: the slowest part of the test is this compile (x86-64 doubles: the same bits as -O1)
    flags = ["-std=c++17", "-O0", "-fno-exceptions", "-Wall", "-Wextra", "-Werror"]
    include = [f"-I{ROOT / 'include'}", f"-I{folder}"]
    build = subprocess.run(
        [cxx, *flags, *include, str(folder / "multi.cpp"), "-o", str(exe)],
        capture_output=True,
        text=True,
    )
    assert build.returncode == 0, build.stderr[-3000:]
    run = subprocess.run([exe], input="".join(stdin), capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    out, cpp = run.stdout.split("\n"), {}
    for at, (ns, python) in enumerate(expected.items()):
        rows = out[at * T.size : (at + 1) * T.size]
        cpp[ns] = np.array([[float(v) for v in row.split()] for row in rows]).reshape(python.shape)
    return expected, cpp, out[len(expected) * T.size :]


def test_exported_multi_input_headers_give_pythons_commands(tmp_path, compiler):  # noqa: F811
    cases = {f"lc{k}": _load_compensated(k) for k in LC_CASES}
    cases.update({f"cf{k}": _coupled(k) for k in CF_CASES})
    cases.update({f"cf_root{k}": _extra_coupled(k) for k in range(2)})
    expected, cpp, rest = run_exported(cases, tmp_path, compiler, SPOILED)
    for ns, python in expected.items():
        assert np.all(np.isfinite(python)) and np.ptp(python) > 0.1, ns  # exercised
        np.testing.assert_array_equal(cpp[ns], python, err_msg=ns)  # measured: bit for bit
    assert rest[0] == "LoadPlayInverse: switch_travel must be > 0 (got -1)", rest[0]
    assert "the coupling's diagonal must be zero" in rest[1], rest[1]


def test_the_headers_name_the_class_and_its_step(tmp_path):
    """The header is the constants and the builder: no JSON, no exceptions, the step named."""
    _load_compensated(1).to_json(tmp_path / "lc.json")
    _coupled(1).to_json(tmp_path / "cf.json")
    lc, cf = cpp_header(tmp_path / "lc.json"), cpp_header(tmp_path / "cf.json", "wrist")
    assert "using Compensator = tendonsheath::LoadCompensated<tendonsheath::ModelInverse>;" in lc
    assert "c.step(y_d, dt, load)" in lc and "inline constexpr tendonsheath::LoadTerms" in lc
    assert "using Compensator = tendonsheath::CoupledFeedforward;" in cf
    assert "namespace wrist {" in cf and "inline constexpr std::size_t joints = 3;" in cf
    for text in (lc, cf):
        assert "json" not in text.replace(".json", "") and "throw" not in text


def test_an_angle_dependent_base_points_to_the_json_loader(tmp_path):
    """An AngleDependent's laws are no fields: one line naming the loader to use instead."""
    model = Coupled(
        [_angle_backlash(np.random.default_rng(0)), Polynomial(degree=1)],
        np.array([[0.0, 0.1], [0.0, 0.0]]),
    )
    CoupledFeedforward(model).to_json(tmp_path / "ad.json")
    with pytest.raises(ValueError, match=r"json_multi_input\.hpp") as err:
        cpp_header(tmp_path / "ad.json")
    assert "AngleDependent" in str(err.value) and "\n" not in str(err.value)
    assert isinstance(CoupledFeedforward(model).joints[0], InverseFeedforward)
