"""Shared by the swell module's tests: the `swell` command of the same build (SWELL_COMMAND,
set by ctest) and small cases, so that each test compares the module with the command on the
same input."""
import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

import swell

REPOSITORY = pathlib.Path(__file__).resolve().parents[2]
COMMAND = os.environ.get("SWELL_COMMAND", str(REPOSITORY / "build" / "cli" / "swell"))
EXTERNAL = REPOSITORY.parent / "shared" / "data" / "external"


def run(*arguments, expect=0):
    """Runs the command; returns (stdout, stderr); asserts the exit code (expect=None: a
    verdict, 0 pass or 1 fail)."""
    done = subprocess.run([COMMAND, *map(str, arguments)], capture_output=True, text=True)
    allowed = (0, 1) if expect is None else (expect,)
    assert done.returncode in allowed, f"exit {done.returncode}: {done.stderr}{done.stdout[-2000:]}"
    return done.stdout, done.stderr


def run_json(*arguments, expect=0):
    return json.loads(run(*arguments, "--json", "-", expect=expect)[0])


def command_error(*arguments):
    """The message the command prints with exit code 2, without its "swell: error: " prefix."""
    _, err = run(*arguments, expect=2)
    first = err.strip().splitlines()[0]
    assert first.startswith("swell: error: "), err
    return first[len("swell: error: "):]


SEA = {
    "grid": {"n": [64, 64], "length": [200.0, 200.0]},
    "time": {"t0": 0.0, "dt": 0.5, "frames": 4},
    "spectrum": {"model": "jonswap", "hs": 3.0, "tp": 8.0, "gamma": 3.3},
    "spreading": {"model": "cos2s", "s": 10.0, "wind_dir_deg": 30.0},
    "synthesis": {"choppiness": 0.8, "seed": 5},
}


@pytest.fixture
def sea():
    """A small JONSWAP case as a dict of sections (a fresh copy each time)."""
    return json.loads(json.dumps(SEA))


def synthesized(tmp_path, case_dict, precision="fp64", impl="fftw", name="sea"):
    """The command's frames of a case (npy, so that NumPy reads them back exactly): the folder
    and the arrays {field: (frames, ny, nx)}."""
    case = swell.Case(case_dict)
    case_path = tmp_path / f"{name}.toml"
    case_path.write_text(case.to_toml())
    out = tmp_path / name
    run("synth", "--case", case_path, "--impl", impl, "--precision", precision, "--format", "npy",
        "--out", out, "--json", out.with_suffix(".json"))
    return out, load_frames(out, case.frames)


def load_frames(folder, frames):
    arrays = {}
    for field, suffix in zip(swell.FIELDS, ("h", "sx", "sy", "dx", "dy", "J")):
        paths = [folder / f"frame_{f:04d}_{suffix}.npy" for f in range(frames)]
        if paths[0].exists():
            arrays[field] = np.stack([np.load(p) for p in paths])
    return arrays


def without_times(document):
    """A gate's JSON without what differs between two runs of the same judgement: the wall
    times, and the case's name (a file for the command, none for arrays)."""
    return {k: v for k, v in document.items() if k not in ("seconds", "read_seconds", "case")}
