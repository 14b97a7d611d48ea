"""swell.synth against `swell synth`: the same numbers, bit for bit, in both precisions, on
grids, lattices and probes."""
import numpy as np
import pytest

import swell
from conftest import load_frames, run, synthesized


@pytest.mark.parametrize("precision,dtype", [("fp64", np.float64), ("fp32", np.float32)])
def test_grid_frames_equal_the_commands(tmp_path, sea, precision, dtype):
    _, expected = synthesized(tmp_path, sea, precision=precision)
    frames = swell.synth(sea, precision="float64" if precision == "fp64" else "float32")
    assert set(frames) == set(swell.FIELDS)
    for field in swell.FIELDS:
        assert frames[field].dtype == dtype and frames[field].shape == (4, 64, 64)
        assert frames[field].flags["C_CONTIGUOUS"]
        np.testing.assert_array_equal(frames[field], expected[field], err_msg=field)


def test_fields_and_frames_choose_what_is_made(sea):
    all_frames = swell.synth(sea, impl="radix2", precision="float64")
    some = swell.synth(sea, impl="radix2", precision="float64", frames=2, fields=["height", "disp_x"])
    assert set(some) == {"height", "disp_x"} and some["height"].shape == (2, 64, 64)
    np.testing.assert_array_equal(some["disp_x"], all_frames["disp_x"][:2])


def test_lattice_frames_equal_the_commands(tmp_path, sea):
    case_path = tmp_path / "grid.toml"
    case_path.write_text(swell.Case(sea).to_toml())
    out = tmp_path / "lattice"
    run("synth", "--case", case_path, "--impl", "lattice:fft=fftw", "--points", 1024,
        "--precision", "fp64", "--out", out)
    lattice_case = swell.Case(out / "case.toml")
    assert lattice_case.kind == "lattice" and lattice_case.n == (1024,)
    frames = swell.synth(lattice_case, precision="float64")
    assert frames["height"].shape == (4, 1024)
    np.testing.assert_array_equal(frames["height"], load_frames(out, 4)["height"])
    # The command's spelling of the same choice.
    spelled = swell.synth(lattice_case, impl="lattice:fft=fftw", precision="float64", fields=["height"])
    np.testing.assert_array_equal(spelled["height"], frames["height"])
    with pytest.raises(ValueError, match="samples a grid"):
        swell.synth(sea, impl="lattice")


PROBES = {
    "sampling": {"kind": "probes", "positions": [[0.0, 0.0], [10.0, 0.0], [0.0, 10.0]]},
    "time": {"t0": 0.0, "dt": 0.5, "samples": 2048},
    "physics": {"depth": 30.0},
    "spectrum": {"model": "jonswap", "hs": 3.0, "tp": 10.0, "gamma": 3.3},
    "spreading": {"model": "cos2s", "s": 10.0, "wind_dir_deg": 30.0},
    "synthesis": {"seed": 1, "amplitudes": "rayleigh", "frequencies": "uniform",
                  "repeat_period": 1024.0, "directions": "single_per_frequency",
                  "omega_cutoff": [0.25, 3.0]},
}


def test_probe_series_equal_the_commands(tmp_path):
    case = swell.Case(PROBES)
    path = tmp_path / "probes.toml"
    path.write_text(case.to_toml())
    run("synth", "--case", path, "--out", tmp_path / "probes")
    expected = np.loadtxt(tmp_path / "probes" / "elevation.csv", delimiter=",", skiprows=1)[:, 1:]
    series = swell.synth(case)["elevation"]
    assert series.shape == (2048, 3)
    np.testing.assert_array_equal(series, expected)


def test_bad_requests_are_refused(sea):
    with pytest.raises(ValueError, match="frames"):
        swell.synth(sea, frames=0)
    with pytest.raises(ValueError, match="precision"):
        swell.synth(sea, precision="float16")
    with pytest.raises(ValueError, match="not_a_backend"):
        swell.synth(sea, impl="not_a_backend")
    with pytest.raises(ValueError, match="curl"):
        swell.synth(sea, fields=["curl"])


def test_memory_rule_is_the_commands(sea):
    # A grid whose arrays the machine cannot hold is refused before any work, as the command
    # refuses it, naming what to reduce.
    sea["grid"] = {"n": [131072, 131072], "length": [2.0e5, 2.0e5]}
    with pytest.raises(ValueError, match=r"swell.synth needs about .* use a smaller grid"):
        swell.synth(sea)
