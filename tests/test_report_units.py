"""One angle unit per report: the calibration's figures too (a share of the range has none)."""

import math
from types import SimpleNamespace

import pytest

from tendonsheath.report.build import _calibration_tables
from tendonsheath.report.units import unit_of_key


@pytest.mark.parametrize("unit", ["deg", "rad"])
def test_the_calibration_table_is_in_the_reports_unit(unit):
    result = SimpleNamespace(
        calibration={"rmse": 0.01, "nrmse": 0.02, "seconds": 3.0, "fits": {}}, identified=None
    )
    text = _calibration_tables(result, unit)
    shown = math.degrees(0.01) if unit == "deg" else 0.01
    assert f"rmse [{unit}]" in text and f"{shown:.4g}" in text
    assert "nrmse [" not in text and "0.02" in text  # a share: neither unit nor conversion


def test_nrmse_has_no_angle_unit():
    assert unit_of_key("nrmse") == "" and unit_of_key("rmse") == "rad"
