#!/usr/bin/env bash
# Installs a built wheel into a fresh venv outside the source tree and runs the quick start
# from there, so `import tendonsheath` can only find the installed wheel. The wheel alone is the
# light core (no extra): it must install none of the extras' packages and still simulate,
# identify, compensate and run the commands.
# Usage: bash tests/wheel_smoke.sh dist/tendonsheath-*.whl
set -euo pipefail
wheel=$(realpath "${1:?usage: wheel_smoke.sh WHEEL}")
python=${PYTHON:-python3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

"$python" -m venv venv
venv/bin/python -m pip install --quiet "$wheel"

# a light core (issue 26): the optional packages are extras, none installed with the wheel
for extra in plotly h5py openpyxl; do
  if venv/bin/python -m pip show --quiet "$extra" > /dev/null 2>&1; then
    echo "FAIL: pip install of the wheel installed $extra (an extra)"; exit 1
  fi
done
# ... and the report without its extra is one line naming it, and exit 2 (checked before it runs)
set +e
out=$(venv/bin/tendonsheath demo --out "$work/demo-out" 2>&1); code=$?
set -e
want="error: the HTML report needs plotly: pip install 'tendonsheath[report]'"
[ "$code" = 2 ] && [ "$out" = "$want" ] || { echo "FAIL: demo without plotly: $code '$out'"; exit 1; }

expected=$(venv/bin/python -c "from importlib.metadata import version; print(version('tendonsheath'))")
for cmd in "venv/bin/tendonsheath --version" "venv/bin/python -m tendonsheath --version"; do
  got=$($cmd)
  [ "$got" = "tendonsheath $expected" ] || { echo "FAIL: '$cmd' printed '$got'"; exit 1; }
done
help=$(venv/bin/tendonsheath --help)
for command in demo identify compare; do
  grep -q "$command" <<< "$help" || { echo "FAIL: tendonsheath --help lists no $command"; exit 1; }
done

venv/bin/python - "$work" <<'PY'
import subprocess
import sys

import numpy as np

import tendonsheath as ts
from tendonsheath import _core

venv = sys.argv[1]
for module in (ts, _core):
    assert module.__file__.startswith(venv), f"{module.__name__} from {module.__file__}"
# the extension uses the process's libstdc++ (one copy), not a static one of its own
needed = subprocess.run(["ldd", _core.__file__], capture_output=True, text=True).stdout
assert "libstdc++.so.6" in needed, needed
assert ts.__version__ == subprocess.run(
    [f"{venv}/venv/bin/tendonsheath", "--version"], capture_output=True, text=True
).stdout.split()[1]

# typed (PEP 561): the marker, and the extension's stubs from nanobind's stub generator
from pathlib import Path

package = Path(ts.__file__).parent
assert (package / "py.typed").is_file(), "py.typed is not in the wheel"
stubs = (package / "_core.pyi").read_text()
assert "class PullPullPlant" in stubs and "def shape_integrals(" in stubs, "_core.pyi incomplete"

# a model: exact backlash on a unit sine peaks at c (1 - B) and -c (1 - B)
t = np.arange(0.0, 4.0, 1e-3)
x = np.sin(2 * np.pi * t)
y = ts.models.Backlash(c_r=2.0, c_l=2.0, B_r=0.1, B_l=0.1).simulate(t, x)
assert abs(y.max() - 1.8) < 1e-3 and abs(y.min() + 1.8) < 1e-3, (y.min(), y.max())

# validation formats its message (the C++ path that crashed in issue 15's story)
try:
    ts.models.Backlash(B_r=-1.0)
except ValueError as e:
    assert "B_r" in str(e), e
else:
    raise AssertionError("Backlash(B_r=-1) was accepted")

# a plant: the pull-pull pair follows the motor through its dead zone, finite and bounded
route = ts.Route.arcs([(0.5, 0.0), (0.5, np.pi / 2)])
plant = ts.PullPullPlant(route=route, friction=0.1, stiffness=5e3, pretension=20.0,
                         proximal_radius=15e-3, distal_radius=15e-3, elements=40)
q = plant.simulate(t, x)
assert np.all(np.isfinite(q)), "plant output not finite"
assert 0.5 < np.ptp(q) / np.ptp(x) <= 1.0 + 1e-9, np.ptp(q)

# identify and compensate on the core install: the backlash's parameters from its own output,
# and its inverse feedforward tracking 1.5 sin: rms error ~1e-5 of the uncompensated one's
# (1e-5 against 1.0 rad); 1e-2 leaves the margin
truth = ts.models.Backlash(c_r=2.0, c_l=2.0, B_r=0.1, B_l=0.1)
fit = ts.identify(ts.models.Backlash, t, x, y)
assert abs(fit.model.params["B_r"] - 0.1) < 1e-3, fit.model.params
ff = ts.compensate.InverseFeedforward(fit.model, smoothing=0.03)
yd = 1.5 * x
u = np.array([ff.step(v, 1e-3) for v in yd])
late = t >= 1.0
err_ff = np.sqrt(np.mean((truth.simulate(t, u) - yd)[late] ** 2))
err_none = np.sqrt(np.mean((truth.simulate(t, yd) - yd)[late] ** 2))
assert err_ff < 1e-2 * err_none, (err_ff, err_none)
print(f"wheel smoke: tendonsheath {ts.__version__} from {ts.__file__}: quick start passed")
PY
