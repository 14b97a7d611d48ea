"""swell.gate against `swell gate`: the same report for the same frames, in every dtype and
memory layout; bad input with the command's message; the GIL released."""
import json
import threading
import time

import numpy as np
import pytest

import swell
from conftest import command_error, run, synthesized, without_times


def command_report(folder, expect=0):
    out, _ = run("gate", "--case", folder / "case.toml", "--json", "-", "--quiet", expect=expect)
    return json.loads(out)


@pytest.mark.parametrize("precision", ["fp64", "fp32"])
def test_report_equals_the_commands(tmp_path, sea, precision):
    folder, frames = synthesized(tmp_path, sea, precision=precision)
    expected = command_report(folder)
    report = swell.gate(swell.Case(folder / "case.toml"), **frames)
    assert report.passed and expected["pass"]
    assert without_times(json.loads(report.to_json())) == without_times(expected)
    assert len(report.checks) == len(expected["checks"]) and not report.failed
    first = report.checks[0]
    assert first.verdict == "pass" and first.reason


def test_case_files_are_read_as_the_command_reads_them(tmp_path, sea):
    # No arrays: the frames the case's [input] names, here EXR (float32) and TIFF, read by the
    # command's readers (TIFF through the OpenImageIO module).
    for image in ("exr", "tiff"):
        case_path = tmp_path / f"{image}.toml"
        case_path.write_text(swell.Case(sea).to_toml())
        folder = tmp_path / image
        run("synth", "--case", case_path, "--impl", "fftw", "--format", image, "--out", folder)
        expected = command_report(folder)
        report = swell.gate(folder / "case.toml")
        assert report.passed and without_times(report.document) == without_times(expected)
        assert report.document["case"] == expected["case"]
    with pytest.raises(ValueError, match="no frames to read"):
        swell.gate(sea)


def test_half_frames_equal_the_commands(tmp_path, sea):
    folder, frames = synthesized(tmp_path, sea, precision="fp32")
    for f in range(4):
        for suffix, field in (("h", "height"), ("sx", "slope_x"), ("sy", "slope_y"),
                              ("dx", "disp_x"), ("dy", "disp_y"), ("J", "jacobian")):
            np.save(folder / f"frame_{f:04d}_{suffix}.npy", frames[field][f].astype("<f2"))
    expected = command_report(folder)
    halves = {field: values.astype(np.float16) for field, values in frames.items()}
    report = swell.gate(swell.Case(folder / "case.toml"), **halves)
    assert report.document["storage_roundoff"] == expected["storage_roundoff"] > 0
    assert without_times(report.document) == without_times(expected)


@pytest.mark.parametrize("dtype", ["<c16", "<c8"])
def test_complex_frames_equal_the_commands(tmp_path, sea, dtype):
    # An engine that hands over its inverse transform's complex output: the imaginary parts,
    # here a small stray part, are what the Hermitian check measures.
    folder, frames = synthesized(tmp_path, sea)
    rng = np.random.default_rng(8)
    complex_heights = (frames["height"] + 1e-9j * rng.standard_normal(frames["height"].shape)).astype(dtype)
    for f in range(4):
        np.save(folder / f"frame_{f:04d}_h.npy", complex_heights[f])
    expected = command_report(folder, expect=None)
    report = swell.gate(swell.Case(folder / "case.toml"), **dict(frames, height=complex_heights))
    assert without_times(report.document) == without_times(expected)
    assert report.passed == expected["pass"]
    # 1e-9 m of imaginary part is far above fp64's rounding and within float32's.
    hermitian = {c.name: c.verdict for c in report.checks if c.name.startswith("hermitian")}
    assert "fail" in hermitian.values() if dtype == "<c16" else "fail" not in hermitian.values(), hermitian


def test_every_layout_gives_the_same_report(sea):
    frames = swell.synth(sea, precision="float64", fields=["height", "disp_x"])
    reference = without_times(swell.gate(sea, power=False, **frames).document)
    h, dx = frames["height"], frames["disp_x"]
    big = np.zeros((4, 128, 192))
    big[:, ::2, ::3] = h
    layouts = {
        "fortran": (np.asfortranarray(h), np.asfortranarray(dx)),
        "strided view": (big[:, ::2, ::3], dx),
        "byte-swapped": (h.astype(">f8"), dx.astype(">f8")),
        "transposed twice": (np.ascontiguousarray(h.transpose(0, 2, 1)).transpose(0, 2, 1), dx),
        "list of frames": ([h[f] for f in range(4)], dx),
    }
    for name, (height, disp_x) in layouts.items():
        report = swell.gate(sea, power=False, height=height, disp_x=disp_x)
        assert without_times(report.document) == reference, name


def test_one_transposed_field_fails_and_is_named(sea):
    frames = swell.synth(sea, precision="float64", fields=["height", "disp_x"])
    report = swell.gate(sea, power=False, height=frames["height"],
                        disp_x=frames["disp_x"].transpose(0, 2, 1))
    assert not report.passed
    assert [c.name for c in report.failed] == ["derived.disp_x"]
    assert "transposed" in report.failed[0].reason


def test_junit_and_text_are_the_commands_renderings(tmp_path, sea):
    folder, frames = synthesized(tmp_path, sea)
    report = swell.gate(swell.Case(folder / "case.toml"), **frames)
    assert report.to_junit().startswith("<?xml") and "derived.jacobian" in report.to_junit()
    assert "verdict: PASS" in str(report)


def test_bad_arrays_raise_the_commands_messages(tmp_path, sea):
    folder, frames = synthesized(tmp_path, sea)
    case = swell.Case(folder / "case.toml")
    # A frame of the wrong shape: the command's message for that .npy file, with the array named
    # instead of the file.
    np.save(folder / "frame_0002_h.npy", frames["height"][2][:, :32])
    expected = command_error("gate", "--case", folder / "case.toml")
    bad = [frames["height"][f] for f in range(4)]
    bad[2] = bad[2][:, :32]
    with pytest.raises(ValueError) as error:
        swell.gate(case, height=bad)
    assert str(error.value).startswith("height, frame 2: ")
    assert str(error.value).split(": ", 1)[1] == expected.split(": ", 1)[1]
    # A NaN, likewise.
    nan = frames["height"].copy()
    nan[1, 3, 5] = np.nan
    np.save(folder / "frame_0002_h.npy", frames["height"][2])
    np.save(folder / "frame_0001_h.npy", nan[1])
    expected = command_error("gate", "--case", folder / "case.toml")
    with pytest.raises(ValueError) as error:
        swell.gate(case, height=nan)
    assert str(error.value).split(": ", 1)[1] == expected.split(": ", 1)[1]
    assert "(i, j) = (5, 3)" in str(error.value)
    with pytest.raises(ValueError, match="dtype int64"):
        swell.gate(case, height=frames["height"].astype(np.int64))
    with pytest.raises(ValueError, match="3 frames where the case has"):
        swell.gate(case, height=frames["height"][:3])
    with pytest.raises(ValueError, match="shape"):
        swell.gate(case, height=frames["height"][None])
    with pytest.raises(ValueError, match="not a field"):
        swell.gate(case, heigth=frames["height"])
    with pytest.raises(ValueError, match="alpha"):
        swell.gate(case, alpha=1.5, height=frames["height"])
    with pytest.raises(ValueError, match="masked"):
        swell.gate(case, height=np.ma.masked_invalid(frames["height"]))


def test_probe_series_report_equals_the_commands(tmp_path):
    from test_synth import PROBES
    case = swell.Case(PROBES)
    path = tmp_path / "probes.toml"
    path.write_text(case.to_toml())
    folder = tmp_path / "probes"
    run("synth", "--case", path, "--out", folder)
    # The series as .npy, read by the command as the module reads the array (a CSV's rounding
    # is its printed digits'; an array's is its dtype's).
    series = np.loadtxt(folder / "elevation.csv", delimiter=",", skiprows=1)[:, 1:]
    np.save(folder / "elevation.npy", series)
    text = (folder / "case.toml").read_text()
    text = text[:text.index("[input]")] + '[input]\nfiles = "elevation.npy"\n'
    (folder / "case.toml").write_text(text)
    expected = command_report(folder)
    report = swell.gate(swell.Case(folder / "case.toml"), elevation=series)
    assert report.passed == expected["pass"]
    assert without_times(report.document) == without_times(expected)


def test_cascade_set_is_judged_per_cascade():
    from conftest import REPOSITORY
    case = swell.Case(REPOSITORY / "data" / "cases" / "three_cascades.toml")
    made = swell.synth(case, precision="float64", fields=["height"])
    cascades = [made[f"cascade{k}"] for k in range(3)]
    report = swell.gate(case, cascades=cascades, power=False)
    assert report.passed, str(report)
    assert any(c.name.startswith("cascade1.") for c in report.checks)
    # Cascade 1's heights handed in twice as large: that cascade's energy fails, by name.
    doubled = [dict(c) for c in cascades]
    doubled[1] = {"height": 2 * cascades[1]["height"]}
    failed = {c.name for c in swell.gate(case, cascades=doubled, power=False).failed}
    assert "cascade1.energy" in failed and not any(n.startswith("cascade0.") for n in failed)


def test_gate_releases_the_gil(sea):
    # While a gate runs on another thread, this one keeps running Python: some of its ticks
    # fall inside a gate call, not only between calls. A gate holding the GIL would let no
    # tick be stamped between its start and its end (a tick waiting for the GIL is stamped
    # once the gate returns). Timestamps, not a tick count, so that a loaded machine that
    # wakes this thread rarely does not fail it.
    frames = swell.synth(sea, precision="float64")
    ticks, calls = [], []
    done = threading.Event()

    def judge():
        for _ in range(3):
            start = time.monotonic()
            swell.gate(sea, **frames)
            calls.append((start, time.monotonic()))
        done.set()

    worker = threading.Thread(target=judge)
    worker.start()
    while not done.is_set():
        ticks.append(time.monotonic())
        done.wait(0.001)
    worker.join()
    # Within the first three quarters of a call: a tick that waited for the GIL would be
    # stamped only as the call returns, at its very end.
    inside = [t for t in ticks if any(start < t < start + 0.75 * (end - start) for start, end in calls)]
    assert len(inside) >= 3, (len(ticks), calls)


def test_power_equals_the_commands(tmp_path, sea):
    path = tmp_path / "case.toml"
    path.write_text(swell.Case(sea).to_toml())
    text, document = swell.power(path)
    out, _ = run("gate", "--power", "--case", path)
    assert text == out
    assert document == json.loads(run("gate", "--power", "--case", path, "--json", "-")[0])
