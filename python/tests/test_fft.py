"""swell.fft against `swell fft` and NumPy: unnormalized both ways, every dtype and layout."""
import numpy as np
import pytest

import swell
from conftest import command_error, run


def command_fft(tmp_path, x, *flags):
    np.save(tmp_path / "in.npy", x)
    run("fft", "--impl", "fftw", "--in", tmp_path / "in.npy", "--out", tmp_path / "out.npy", *flags)
    return np.load(tmp_path / "out.npy")


@pytest.mark.parametrize("dtype", [np.complex64, np.complex128])
def test_c2c_equals_the_command_and_numpy(tmp_path, dtype):
    rng = np.random.default_rng(3)
    x = (rng.standard_normal((12, 20)) + 1j * rng.standard_normal((12, 20))).astype(dtype)
    forward = swell.fft(x)
    assert forward.dtype == dtype and forward.shape == x.shape
    np.testing.assert_array_equal(forward, command_fft(tmp_path, x))
    inverse = swell.fft(x, inverse=True)
    np.testing.assert_array_equal(inverse, command_fft(tmp_path, x, "--inverse"))
    tolerance = 1e-4 if dtype == np.complex64 else 1e-12
    np.testing.assert_allclose(forward, np.fft.fft2(x), atol=tolerance * np.abs(x).sum())
    # Unnormalized: the inverse of the forward is N·x, not x.
    np.testing.assert_allclose(swell.fft(forward, inverse=True), x.size * x, atol=tolerance * x.size * np.abs(x).sum())


def test_r2c_and_c2r(tmp_path):
    rng = np.random.default_rng(4)
    x = rng.standard_normal((8, 30))
    half = swell.fft(x)
    assert half.shape == (8, 16) and half.dtype == np.complex128
    np.testing.assert_array_equal(half, command_fft(tmp_path, x))
    np.testing.assert_allclose(half, np.fft.rfft2(x), atol=1e-12 * np.abs(x).sum())
    back = swell.fft(half, c2r=True)
    np.testing.assert_array_equal(back, command_fft(tmp_path, half, "--c2r"))
    np.testing.assert_allclose(back, x.size * x, atol=1e-11 * x.size)
    odd = swell.fft(swell.fft(x[:, :29]), c2r=True, nx=29)
    np.testing.assert_allclose(odd, x[:, :29].size * x[:, :29], atol=1e-11 * x.size)


def test_layouts_are_read_as_numpy_indexes_them():
    rng = np.random.default_rng(5)
    x = rng.standard_normal((16, 24)) + 1j * rng.standard_normal((16, 24))
    expected = swell.fft(x)
    for view in (np.asfortranarray(x), x.astype(">c16"),
                 np.pad(x, ((0, 16), (0, 24)))[::1, ::1][:16, :24],
                 np.repeat(np.repeat(x, 2, axis=0), 3, axis=1)[::2, ::3]):
        np.testing.assert_array_equal(swell.fft(view), expected)


def test_every_backend_agrees():
    rng = np.random.default_rng(6)
    x = rng.standard_normal((16, 32)) + 1j * rng.standard_normal((16, 32))
    reference = np.fft.fft2(x)
    for impl in swell.backends():
        if impl == "null":
            continue
        np.testing.assert_allclose(swell.fft(x, impl=impl), reference, atol=1e-9 * np.abs(x).sum(),
                                   err_msg=impl)


def test_bad_input_has_the_commands_message(tmp_path):
    x = np.ones(8, dtype=np.float16)
    np.save(tmp_path / "x.npy", x)
    expected = command_error("fft", "--impl", "fftw", "--in", tmp_path / "x.npy", "--out", tmp_path / "y.npy")
    with pytest.raises(ValueError) as error:
        swell.fft(x)
    assert str(error.value) == expected.replace(str(tmp_path / "x.npy"), "x")
    nan = np.ones((2, 4))
    nan[1, 2] = np.nan
    with pytest.raises(ValueError, match=r"element \[1, 2\].*NaN"):
        swell.fft(nan)
    with pytest.raises(ValueError, match="--inverse needs complex input"):
        swell.fft(np.ones(8), inverse=True)
    with pytest.raises(ValueError, match="rank 3"):
        swell.fft(np.ones((2, 2, 2)))
    with pytest.raises(ValueError, match="dtype int64"):
        swell.fft(np.arange(8))


def test_backends_are_the_commands(tmp_path):
    out, _ = run("fft", "--help")
    listed = out[out.index("transform backend (") + len("transform backend ("):].split(")")[0]
    assert swell.backends() == listed.split(", ")
    np.save(tmp_path / "x.npy", np.ones(8))
    expected = command_error("fft", "--impl", "nope", "--in", tmp_path / "x.npy", "--out", tmp_path / "y.npy")
    with pytest.raises(ValueError) as error:
        swell.fft(np.ones(8), impl="nope")
    assert str(error.value) == expected
