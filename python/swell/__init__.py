"""swell from Python: the gate, spectra, synthesis, fits and transforms on NumPy arrays.

The same C++ libraries as the ``swell`` command, with the same rules and messages
(docs/python.md). Bad input raises :class:`InvalidInput`, a ``ValueError``, with the message the
command prints before exiting with code 2; a failed check is a result (``Report.passed``), never
an exception. Long work (synthesis, the gate, fits, transforms) releases the GIL.

Units are the case files' (docs/conventions.md): metres, seconds, rad/s, rad/m; directions in
degrees counter-clockwise from +x, the direction the waves travel toward.
"""
import json
import os
from collections import namedtuple

import numpy as np

_bundled_image_module = os.path.join(os.path.dirname(__file__), "libswell_openimageio.so")
if os.path.exists(_bundled_image_module):
    # A pip-installed package carries the TIFF/PNG reader beside itself (python/setup.py).
    os.environ.setdefault("SWELL_OPENIMAGEIO_MODULE", _bundled_image_module)

from . import _swell  # noqa: E402
from ._arrays import field_frames, npy_ready  # noqa: E402
from ._tables import with_tables  # noqa: E402

InvalidInput = _swell.InvalidInput
NumericalError = _swell.NumericalError

__all__ = ["Case", "Spectrum", "Report", "Check", "Fit", "Estimate", "InvalidInput",
           "NumericalError", "spectrum", "synth", "gate", "power", "fit", "fft", "backends",
           "FIELDS"]

#: The fields of a frame, in swell's order (docs/conventions.md §Fields).
FIELDS = ("height", "slope_x", "slope_y", "disp_x", "disp_y", "jacobian")


class Case:
    """A case: its grid (or lattice, probes or cascades), times, sea and declarations.

    ``Case(source)`` takes a path to a case file (str or os.PathLike), the text of one (a str
    holding a newline or ``=``), or a dict of its sections, as the file would hold them::

        swell.Case({"grid": {"n": [128, 128], "length": [200.0, 200.0]},
                    "time": {"dt": 0.5, "frames": 8},
                    "spectrum": {"model": "jonswap", "hs": 3.0, "tp": 8.0},
                    "spreading": {"model": "cos2s", "s": 10.0}})

    Where a tabulated spectrum goes (``model = "table"``), an xarray ``DataArray`` efth(freq,
    dir) may stand for its ``file`` (docs/python.md §wavespectra). Files a case names are
    relative to the case file, or to the current directory for a case without a file.
    """

    def __init__(self, source):
        if isinstance(source, Case):
            self._case = source._case
        elif isinstance(source, dict):
            with with_tables(source) as sections:
                self._case = _swell.Case.from_dict(_plain(sections))
        elif isinstance(source, (str, os.PathLike)):
            text = os.fspath(source)
            if isinstance(source, str) and ("\n" in text or "=" in text):
                self._case = _swell.Case.from_toml(text)
            else:
                if not os.path.isfile(text):
                    raise InvalidInput(f"{text}: no such case file")
                self._case = _swell.Case.from_path(text)
        else:
            raise InvalidInput(f"Case takes a path, TOML text or a dict of sections, not a "
                               f"{type(source).__name__}")

    kind = property(lambda self: self._case.kind, doc='"grid", "lattice", "probes" or "cascades"')
    n = property(lambda self: tuple(self._case.n), doc="(nx, ny), or (N,) on a lattice")
    length = property(lambda self: tuple(self._case.length), doc="(lx, ly) of the patch, m")
    frames = property(lambda self: self._case.frames, doc="frames the case declares")
    times = property(lambda self: np.array(self._case.times), doc="each frame's time, s")
    origin = property(lambda self: self._case.origin, doc="the case file read ('' if none)")

    def describe(self):
        """One line: the sea and its sampling, as the command prints it."""
        return self._case.describe()

    def to_toml(self):
        """The case as a case file's text (what ``swell synth`` writes as case.toml)."""
        return self._case.to_toml()

    def __repr__(self):
        return f"swell.Case({self.describe()!r})"


def _case_of(case):
    return case if isinstance(case, Case) else Case(case)


def _plain(value):
    """NumPy scalars and arrays as the Python numbers and lists a TOML value takes."""
    if isinstance(value, dict):
        return {key: _plain(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(item) for item in value]
    if isinstance(value, np.ndarray):
        return _plain(value.tolist())
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    return value


# ------------------------------------------------------------------------------ spectra


class Spectrum:
    """S(ω), Ψ(k) and the moments of a model or of a case's sea (``swell spectrum``)."""

    def __init__(self, native):
        self._native = native

    def S(self, omega):
        """The omnidirectional spectrum S(ω) in m²·s/rad at ω in rad/s (any shape)."""
        omega = np.asarray(omega, dtype=np.float64)
        values = self._native.S(omega.reshape(-1)).reshape(omega.shape)
        return float(values) if omega.ndim == 0 else values

    def psi(self, kx, ky):
        """The directional wave-number spectrum Ψ(k) in m⁴/rad² at (kx, ky) in rad/m
        (broadcast); 0 at k = 0 (docs/conventions.md §2)."""
        kx, ky = np.broadcast_arrays(np.asarray(kx, dtype=np.float64),
                                     np.asarray(ky, dtype=np.float64))
        values = self._native.psi(kx.reshape(-1), ky.reshape(-1)).reshape(kx.shape)
        return float(values) if kx.ndim == 0 else values

    def moments(self):
        """{m_1, m0, m1, m2, m4, hs, tp, tm01, tm02, te, epsilon4, nu, omega_p}: the command's
        JSON moments (angular frequency; a moment that diverges is None)."""
        return json.loads(self._native.moments_json())

    peak_omega = property(lambda self: self._native.peak_omega, doc="ωp, rad/s")
    parameters = property(lambda self: dict(self._native.parameters),
                          doc="the model's parameters with their defaults filled in")

    def __repr__(self):
        return f"swell.Spectrum({self._native.description!r})"


def spectrum(case_or_model, **params):
    """A spectrum: ``spectrum(case)`` for a case's sea (a Case or what Case takes),
    ``spectrum("jonswap", hs=3, tp=8, gamma=3.3)`` for a model, with ``spreading="cos2s",
    s=10, wind_dir_deg=30`` for its Ψ(k), or ``spectrum(efth)`` for an xarray DataArray
    efth(freq, dir) with its table declarations (docs/python.md)."""
    if _is_data_array(case_or_model):
        grid = {"n": [2, 2], "length": [1.0e4, 1.0e4]}
        table = dict(params, model="table", file=case_or_model)
        return Spectrum(_swell.spectrum_of_case(Case({"grid": grid, "spectrum": table})._case))
    if isinstance(case_or_model, Case) or isinstance(case_or_model, dict) or (
            isinstance(case_or_model, (str, os.PathLike)) and _names_a_case(case_or_model)):
        if params:
            raise InvalidInput(f"{sorted(params)[0]} with a case: the case gives every parameter")
        return Spectrum(_swell.spectrum_of_case(_case_of(case_or_model)._case))
    model = case_or_model
    if not isinstance(model, str):
        raise InvalidInput("spectrum takes a case, a model name or an efth DataArray")
    spreading = params.pop("spreading", "")
    wind_dir = float(params.pop("wind_dir_deg", params.pop("wind_dir", 0.0)))
    spreading_takes = {name for name, _ in _swell.model_parameters(spreading)} if spreading else set()
    numbers, choices, spreading_numbers = {}, {}, {}
    for name, value in params.items():
        if name in spreading_takes and name not in {n for n, _ in _model_parameters(model)}:
            spreading_numbers[name] = float(value)
        elif isinstance(value, str):
            choices[name] = value
        else:
            numbers[name] = float(value)
    return Spectrum(_swell.spectrum_of_model(model, numbers, choices, spreading,
                                             spreading_numbers, wind_dir))


def _model_parameters(model):
    try:
        return _swell.model_parameters(model)
    except ValueError:
        return []


def _names_a_case(text):
    text = os.fspath(text)
    return "\n" in text or "=" in text or text.endswith(".toml") or os.path.isfile(text)


def _is_data_array(value):
    return type(value).__name__ == "DataArray" and hasattr(value, "dims")


# ------------------------------------------------------------------------------ synthesis


def synth(case, impl="fftw", precision="float32", frames=None, fields=None):
    """A case's frames from one transform backend, as ``swell synth`` makes them.

    Returns a dict of arrays, one per field (``fields``: names from FIELDS, default all six):
    (frames, ny, nx) on a grid, (frames, N) on a lattice (``impl="lattice"`` is not needed: a
    lattice case is synthesized on its points through ``impl``'s 1-D transforms). A probes case
    returns {"elevation": (samples, probes)}; a cascade set {"cascade0": {…}, …, "sum": {…}}.
    ``precision``: "float32" or "float64" (the synthesis' and the arrays'); ``frames``: a count
    replacing the case's.
    """
    case = _case_of(case)
    if isinstance(impl, str) and (impl == "lattice" or impl.startswith("lattice:")):
        # The command's --impl lattice[:fft=NAME]: here the case says whether it is a lattice.
        if case.kind != "lattice":
            raise InvalidInput(f"impl {impl!r}: this case samples a {case.kind}; a lattice is the "
                               f"case's ([sampling] kind = \"lattice\"), synthesized through "
                               f"impl = the 1-D transforms' backend")
        option = impl[len("lattice:"):] if impl.startswith("lattice:") else "fft=fftw"
        if not option.startswith("fft=") or option == "fft=":
            raise InvalidInput(f"impl {impl!r}: a lattice takes one option, fft=NAME, as lattice:fft=radix2")
        impl = option[len("fft="):]
    if frames is not None and (isinstance(frames, bool) or not isinstance(frames, (int, np.integer))
                               or frames < 1):
        raise InvalidInput(f"frames = {frames!r}: give a count ≥ 1 (or None: the case's)")
    out = _swell.synth(case._case, impl, precision, int(frames or 0), list(fields or []))
    if case.kind == "probes":
        return {"elevation": out}
    return out


# ------------------------------------------------------------------------------ the gate

Check = namedtuple("Check", "name subject statistic expected bound p alpha verdict reason criterion")
Check.__doc__ = """One check's result: ``statistic`` measured against ``expected``; exact checks
carry their ``bound`` (p and alpha None), statistical ones their ``p`` and the ``alpha`` it was
judged at; ``verdict`` is "pass" or "fail"; ``reason`` says why in the user's terms."""


class Report:
    """A gate's report: ``passed``, ``checks``, ``skipped``, and the command's renderings
    (``str(report)``, ``to_json()``, ``to_junit()``)."""

    def __init__(self, native):
        self._native = native
        self.document = json.loads(native.json())

    passed = property(lambda self: self._native.passed)

    @property
    def checks(self):
        out = []
        for entry in self.document["checks"]:
            statistical = entry.get("p_value") is not None
            out.append(Check(entry["check"], entry.get("subject", ""), entry.get("measured"),
                             entry.get("expected"),
                             None if statistical else entry.get("tolerance"),
                             entry.get("p_value"), entry.get("alpha"),
                             "pass" if entry["pass"] else "fail", entry.get("reason", ""),
                             entry.get("criterion", "")))
        return out

    @property
    def failed(self):
        return [check for check in self.checks if check.verdict == "fail"]

    @property
    def skipped(self):
        return list(self.document.get("skipped", []))

    def to_json(self):
        """The report as ``swell gate --json`` writes it (a str)."""
        return self._native.json()

    def to_junit(self):
        """The report as ``swell gate --junit`` writes it: JUnit XML, one testcase a check."""
        return self._native.junit()

    def __str__(self):
        return self._native.text()

    def __repr__(self):
        return (f"<swell.Report {'passed' if self.passed else 'FAILED'}: "
                f"{len(self.checks)} checks, {len(self.failed)} failed>")


def gate(case, *, alpha=1e-3, threads=0, power=True, cascades=None, sum=None, elevation=None,
         **fields):
    """Judges an engine's arrays against a case, as ``swell gate`` judges its files.

    Fields by name (FIELDS): ``gate(case, height=h, disp_x=dx, …)``, each (frames, ny, nx) —
    (ny, nx) for one frame, (frames, N) on a lattice — in float16, float32 or float64 (complex
    for engines that hand over imaginary parts), in any memory layout. The dtype is the stored
    precision, as a file's type is (docs/conventions.md §Storage precision). A cascade set takes
    ``cascades=[{"height": …}, …]`` and optionally ``sum={…}``; a probes case
    ``elevation=(samples, probes)``. With no arrays, the files the case's [input] names are
    read, as the command reads them (EXR, TIFF, PNG, .npy, raw; CSV or .out series). ``alpha``
    is the family-wise false-alarm rate; ``power`` adds the gate's power table to a single
    surface's report.
    """
    case = _case_of(case)
    native_fields = _field_dict(case, fields)
    native_cascades = []
    if cascades is not None:
        native_cascades = [_field_dict(case, cascade or {}, where=f"cascades[{k}]")
                           for k, cascade in enumerate(cascades)]
    native_sum = None if sum is None else _field_dict(case, sum, where="sum")
    native_elevation = None
    if elevation is not None:
        native_elevation = npy_ready("elevation", elevation, allow_complex=False)
    if case.kind != "probes" and elevation is not None:
        raise InvalidInput("elevation is a probes case's series; this case is judged on frames")
    if case.kind != "cascades" and (cascades is not None or sum is not None):
        raise InvalidInput("cascades and sum belong to a cascade set; this case is one surface")
    if case.kind == "cascades" and fields:
        raise InvalidInput("a cascade set is judged per cascade: give cascades=[{field: array}, …]")
    report = _swell.gate(case._case, native_fields, native_cascades, native_sum, native_elevation,
                         float(alpha), int(threads), bool(power))
    return Report(report)


def _field_dict(case, fields, where=""):
    lattice = case.kind == "lattice"
    out = {}
    for name, value in fields.items():
        if name not in FIELDS and name not in ("h", "sx", "sy", "dx", "dy", "J"):
            prefix = f"{where}: " if where else ""
            raise InvalidInput(f"{prefix}{name}: not a field; give any of {', '.join(FIELDS)}")
        out[name] = field_frames(f"{where} {name}".strip(), value, lattice)
    return out


def power(case, *, alpha=1e-3, threads=0):
    """The gate's power table for a case, without frames (``swell gate --power``): returns
    (text, dict)."""
    text, document = _swell.gate_power(_case_of(case)._case, float(alpha), int(threads))
    return text, json.loads(document)


# ------------------------------------------------------------------------------ fits

Estimate = namedtuple("Estimate", "value standard_error ci95 calibrated method reason")
Estimate.__doc__ = """A fitted parameter: ``ci95`` is (low, high) when ``calibrated``, else None
with ``reason`` saying why (the uncalibrated interval is in Fit.document)."""


class Fit:
    """A JONSWAP fit (``swell fit``): ``estimates`` by name (hs, tp, gamma[, sigma_a, sigma_b]),
    ``truth`` (the case's values), ``converged``, and ``document``, the command's JSON."""

    def __init__(self, document):
        self.document = document
        self.estimates = {
            name: Estimate(e["value"], e["se"], tuple(e["ci95"]) if e["ci95"] else None,
                           e["calibrated"], e["method"], e.get("reason", ""))
            for name, e in document["fit"].items()}
        self.truth = dict(document["truth"])
        self.converged = document["converged"]

    def __getitem__(self, name):
        return self.estimates[name]

    def to_json(self):
        return json.dumps({k: v for k, v in self.document.items() if k != "report"})

    def __repr__(self):
        body = ", ".join(f"{k}={e.value:.6g}" for k, e in self.estimates.items())
        return f"<swell.Fit {body}{'' if self.converged else ' (not converged)'}>"


def fit(case, height=None, *, realizations=None, sigma=False, frame=0, interval="profile"):
    """Fits JONSWAP (Hs, Tp, γ; with ``sigma=True`` σa, σb) to heights by maximum Whittle
    likelihood, as ``swell fit`` does (docs/fit.md). ``height``: (frames, ny, nx) of one
    realization, or ``realizations=[h0, h1, …]``, independent surfaces of the case."""
    case = _case_of(case)
    if (height is None) == (realizations is None):
        raise InvalidInput("give height (one realization) or realizations=[…], not both or neither")
    heights = [height] if realizations is None else list(realizations)
    native = [{"height": field_frames("height" if len(heights) == 1 else f"realizations[{r}]", h,
                                      case.kind == "lattice")}
              for r, h in enumerate(heights)]
    return Fit(json.loads(_swell.fit(case._case, native, bool(sigma), int(frame), str(interval))))


# ------------------------------------------------------------------------------ transforms


def fft(x, impl="fftw", inverse=False, c2r=False, nx=None):
    """One transform of a 1-D or 2-D array by a registered backend, unnormalized in both
    directions as ``swell fft`` (inverse(forward(x)) = N·x, not NumPy's 1/N inverse).

    complex64/complex128: c2c (``inverse`` for e^(+i…)); float32/float64: r2c forward, out
    (…, nx/2+1); ``c2r=True``: a complex half spectrum to real (…, nx), nx = 2(m−1) or ``nx``.
    float32 and complex64 run in fp32, the others in fp64."""
    array = npy_ready("x", x, allow_half=True)
    return _swell.fft(array, impl, bool(inverse), bool(c2r), None if nx is None else int(nx))


def backends():
    """The registered transform backends (names for ``impl``)."""
    return list(_swell.backends())
