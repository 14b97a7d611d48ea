"""swell.spectrum against `swell spectrum`: S(ω) and the moments, of models and of cases."""
import numpy as np
import pytest

import swell
from conftest import REPOSITORY, command_error, run_json

OMEGA = [0.3, 0.5, 0.785, 1.0, 2.5, 6.0]


@pytest.mark.parametrize("model,params,flags", [
    ("jonswap", dict(hs=3, tp=8, gamma=3.3), ["--hs", 3, "--tp", 8, "--gamma", 3.3]),
    ("bretschneider", dict(hs=6.5, tp=10), ["--hs", 6.5, "--tp", 10]),
    ("tma", dict(hs=2, tp=7, depth=10), ["--hs", 2, "--tp", 7, "--depth", 10]),
    ("jonswap", dict(hs=3, tp=8, normalization="dnv"), ["--hs", 3, "--tp", 8, "--normalization", "dnv"]),
])
def test_model_equals_the_command(model, params, flags):
    expected = run_json("spectrum", "--model", model, *flags, "--omega", ",".join(map(str, OMEGA)))
    spectrum = swell.spectrum(model, **params)
    np.testing.assert_array_equal(spectrum.S(OMEGA), expected["S"])
    assert spectrum.moments() == expected["moments"]


def test_case_sea_equals_the_command():
    path = REPOSITORY / "data" / "cases" / "wind_sea_and_swell.toml"
    expected = run_json("spectrum", "--case", path, "--omega", ",".join(map(str, OMEGA)))
    spectrum = swell.spectrum(swell.Case(path))
    np.testing.assert_array_equal(spectrum.S(OMEGA), expected["S"])
    assert spectrum.moments() == expected["moments"]


def test_psi_integrates_to_m0_and_points_down_wind():
    # Ψ over the wave-number plane holds m0 = Hs²/16 (docs/conventions.md §2): the sum over a
    # fine grid of k against the closed form; and its mean direction is the wind's.
    spectrum = swell.spectrum("jonswap", hs=3, tp=8, gamma=3.3, spreading="cos2s", s=10,
                              wind_dir_deg=30)
    k = np.linspace(-1.5, 1.5, 1201)
    kx, ky = np.meshgrid(k, k)
    psi = spectrum.psi(kx, ky)
    dk = k[1] - k[0]
    assert abs(psi.sum() * dk * dk / (3.0 ** 2 / 16) - 1) < 0.01
    direction = np.degrees(np.arctan2((psi * ky).sum(), (psi * kx).sum()))
    assert abs(direction - 30) < 0.5
    assert spectrum.psi(0.0, 0.0) == 0.0
    assert isinstance(spectrum.psi(0.1, 0.0), float)


def test_bad_parameter_is_the_commands_message():
    expected = command_error("spectrum", "--model", "jonswap", "--hs", -3, "--tp", 8)
    with pytest.raises(ValueError) as error:
        swell.spectrum("jonswap", hs=-3, tp=8).S([1.0])
    assert str(error.value) == expected
    with pytest.raises(ValueError, match="spreading"):
        swell.spectrum("jonswap", hs=3, tp=8).psi(0.1, 0.0)
    with pytest.raises(ValueError, match="finite ω ≥ 0"):
        swell.spectrum("jonswap", hs=3, tp=8).S([-1.0])
