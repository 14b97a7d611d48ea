"""The worked example of docs/python.md: a NumPy ocean engine gated inside its own pytest
suite. Tessendorf's synthesis in a dozen lines of NumPy (docs/conventions.md §Amplitudes),
judged by swell.gate — right, and with the two bugs engines ship most: a missing √ on the
amplitudes, and waves travelling against the wind."""
import numpy as np
import pytest

import swell

CASE = {
    "grid": {"n": [128, 128], "length": [400.0, 400.0]},
    "time": {"dt": 0.25, "frames": 8},
    "spectrum": {"model": "jonswap", "hs": 2.5, "tp": 9.0, "gamma": 3.3},
    "spreading": {"model": "cos2s", "s": 12.0, "wind_dir_deg": 45.0},
}


def numpy_engine(case, seed=0, missing_sqrt=False, against_wind=False):
    """Heights (frames, ny, nx): h(x, t) = Σk h̃(k, t) e^(ik·x), with
    h̃(k, t) = h̃0(k) e^(−iωt) + conj(h̃0(−k)) e^(iωt) and h̃0 = ξ/√2 · √(Ψ Δkx Δky / 2)."""
    (nx, ny), (lx, ly) = case.n, case.length
    kx = 2 * np.pi * np.fft.fftfreq(nx, d=lx / nx)
    ky = 2 * np.pi * np.fft.fftfreq(ny, d=ly / ny)
    KX, KY = np.meshgrid(kx, ky)                       # (ny, nx), x fastest
    psi = swell.spectrum(case).psi(KX, KY)
    psi[:, nx // 2] = psi[ny // 2, :] = 0              # the Nyquist row and column carry nothing
    power = psi * (kx[1] - kx[0]) * (ky[1] - ky[0]) / 2
    rng = np.random.default_rng(seed)
    xi = (rng.standard_normal((ny, nx)) + 1j * rng.standard_normal((ny, nx))) / np.sqrt(2)
    h0 = xi * (power if missing_sqrt else np.sqrt(power))
    h0_minus = np.conj(np.roll(np.flip(h0), 1, axis=(0, 1)))   # conj h̃0(−k)
    omega = np.sqrt(9.81 * np.hypot(KX, KY))
    sign = -1 if against_wind else 1
    frames = []
    for t in case.times:
        spectrum = h0 * np.exp(-1j * sign * omega * t) + h0_minus * np.exp(1j * sign * omega * t)
        frames.append(np.fft.ifft2(spectrum).real * nx * ny)
    return np.stack(frames).astype(np.float32)


@pytest.fixture(scope="module")
def case():
    return swell.Case(CASE)


def test_engine_passes_the_gate(case):
    report = swell.gate(case, height=numpy_engine(case))
    assert report.passed, str(report)


def test_missing_square_root_is_caught(case):
    report = swell.gate(case, height=numpy_engine(case, missing_sqrt=True))
    assert not report.passed
    assert "energy" in {check.name for check in report.failed}


def test_waves_against_the_wind_are_caught(case):
    report = swell.gate(case, height=numpy_engine(case, against_wind=True))
    failed = {check.name: check.reason for check in report.failed}
    assert "direction.distribution" in failed
    assert "against the wind" in failed["direction.distribution"]
