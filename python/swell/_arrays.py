"""Arrays handed to swell: checked, then made C-contiguous and little-endian by NumPy's own
conversion, so that every layout (C, Fortran, strided views, byte-swapped) is read as NumPy
indexes it, never misread. A frame is copied once, into the reader's buffer; the gate then
works on float64 values as it does for files."""
import numpy as np

from . import _swell

_DTYPES = {("f", 2), ("f", 4), ("f", 8), ("c", 8), ("c", 16)}


def npy_ready(name, value, allow_complex=True, allow_half=True):
    """`value` as a C-contiguous little-endian array of a dtype an .npy frame may hold."""
    if isinstance(value, np.ma.MaskedArray):
        raise _swell.InvalidInput(f"{name}: a masked array; give the values (every one must be "
                                  f"finite), e.g. a.filled()")
    array = np.asarray(value)
    kind, size = array.dtype.kind, array.dtype.itemsize
    if (kind, size) not in _DTYPES or (kind == "c" and not allow_complex) or (
            kind == "f" and size == 2 and not allow_half):
        wanted = "float16, float32 and float64" if allow_half else "float32 and float64"
        if allow_complex:
            wanted += " (complex64 and complex128 for fields with imaginary parts)"
        raise _swell.InvalidInput(f"{name}: dtype {array.dtype}: swell reads {wanted} arrays")
    array = np.ascontiguousarray(array)
    if array.dtype.byteorder == ">" or (array.dtype.byteorder == "=" and np.little_endian is False):
        array = array.astype(array.dtype.newbyteorder("<"))
    return array


def field_frames(name, value, lattice):
    """A field's frames, each as its .npy file would hold it: (frames, ny, nx) or (ny, nx) on a
    grid, (frames, N) or (N,) on a lattice."""
    sample_axes = 1 if lattice else 2
    if isinstance(value, (list, tuple)) and value and all(np.ndim(item) == sample_axes for item in value):
        # One array a frame: each read on its own, so that one of the wrong shape is named.
        return [npy_ready(name if len(value) == 1 else f"{name}, frame {f}", item)
                for f, item in enumerate(value)]
    array = npy_ready(name, value)
    if array.ndim == sample_axes:
        return [array]
    if array.ndim != sample_axes + 1:
        shape = "(frames, N) or (N,)" if lattice else "(frames, ny, nx) or (ny, nx)"
        raise _swell.InvalidInput(f"{name}: shape {array.shape}: give {shape}")
    return [np.ascontiguousarray(array[f]) for f in range(array.shape[0])]
