"""swell.fit against `swell fit`: the same document for the same heights."""
import json

import pytest

import swell
from conftest import run, synthesized


def test_fit_equals_the_commands(tmp_path, sea):
    sea["grid"] = {"n": [128, 128], "length": [800.0, 800.0]}
    folder, frames = synthesized(tmp_path, sea)
    expected = json.loads(run("fit", "--input", folder, "--case", folder / "case.toml", "--json", "-")[0])
    result = swell.fit(folder / "case.toml", height=frames["height"])
    assert json.loads(result.to_json()) == expected
    hs = result["hs"]
    assert hs.value == expected["fit"]["hs"]["value"] and result.truth["hs"] == 3.0
    assert result.converged


def test_two_realizations_and_sigma(tmp_path, sea):
    sea["grid"] = {"n": [128, 128], "length": [800.0, 800.0]}
    first, frames0 = synthesized(tmp_path, sea, name="a")
    sea["synthesis"]["seed"] = 6
    second, frames1 = synthesized(tmp_path, sea, name="b")
    expected = json.loads(run("fit", "--input", first, "--input", second, "--case",
                              first / "case.toml", "--sigma", "--interval", "wald", "--json", "-")[0])
    result = swell.fit(first / "case.toml", realizations=[frames0["height"], frames1["height"]],
                       sigma=True, interval="wald")
    assert json.loads(result.to_json()) == expected
    assert set(result.estimates) == {"hs", "tp", "gamma", "sigma_a", "sigma_b"}


def test_bad_fit_input(sea):
    frames = swell.synth(sea, precision="float64", fields=["height"])
    with pytest.raises(ValueError, match="not both"):
        swell.fit(sea, height=frames["height"], realizations=[frames["height"]])
    with pytest.raises(ValueError, match="interval"):
        swell.fit(sea, height=frames["height"], interval="bootstrap")
    phillips = dict(sea, spectrum={"model": "phillips", "amplitude": 1e-3, "wind_speed": 10.0})
    phillips.pop("spreading")
    with pytest.raises(ValueError):
        swell.fit(phillips, height=frames["height"])
