"""A wavespectra efth(freq, dir) DataArray wherever a tabulated spectrum goes: the same sea as
the table file it came from, with the same declarations, as keywords or attributes."""
import numpy as np
import pytest

import swell
from conftest import EXTERNAL, REPOSITORY

xarray = pytest.importorskip("xarray")  # python3-xarray: installed by scripts/common.sh

NETCDF = EXTERNAL / "twopeak" / "twopeak_ochi_hubble.nc"
DECLARATIONS = dict(frequency_unit="Hz", density_unit="m2/Hz/deg",
                    direction_convention="nautical_from", direction_unit="deg")


@pytest.fixture(scope="module")
def efth():
    with xarray.open_dataset(NETCDF) as dataset:
        return dataset["efth"].isel(time=0, site=0).load()


def test_data_array_is_the_files_sea(efth):
    from_file = swell.spectrum(swell.Case({
        "grid": {"n": [64, 64], "length": [400.0, 400.0]},
        "spectrum": dict(DECLARATIONS, model="table", file=str(NETCDF), select={"time": 0, "site": 0})}))
    from_keywords = swell.spectrum(efth, **DECLARATIONS)
    from_attributes = swell.spectrum(efth.assign_attrs(**DECLARATIONS))
    omega = np.linspace(0.2, 2.0, 19)
    np.testing.assert_array_equal(from_keywords.S(omega), from_file.S(omega))
    np.testing.assert_array_equal(from_attributes.S(omega), from_file.S(omega))
    assert from_keywords.moments() == from_file.moments()
    np.testing.assert_array_equal(from_keywords.psi([0.02, -0.03], [0.01, 0.04]),
                                  from_file.psi([0.02, -0.03], [0.01, 0.04]))


def test_undeclared_convention_is_named(efth):
    declarations = dict(DECLARATIONS)
    declarations.pop("direction_convention")
    with pytest.raises(ValueError, match="direction_convention"):
        swell.spectrum(efth, **declarations)


def test_gate_against_an_efth_case(efth):
    case = swell.Case({
        "grid": {"n": [64, 64], "length": [1000.0, 1000.0]},
        "time": {"dt": 0.5, "frames": 4},
        "spectrum": dict(DECLARATIONS, file=efth),
        "synthesis": {"seed": 3},
    })
    frames = swell.synth(case, fields=["height"])
    assert swell.gate(case, **frames).passed
    assert not swell.gate(case, height=2 * frames["height"]).passed
