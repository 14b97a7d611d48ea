"""xarray DataArrays where a case takes a tabulated spectrum (model = "table"): an efth(freq,
dir) in wavespectra's layout stands for the table's ``file``. It is written to a temporary
netCDF file that the case reader reads as it reads any table file — the same declared
conventions (frequency_unit, density_unit, direction_convention, direction_unit, select), given
as keys beside it or as the DataArray's attributes — and removed once the case is read."""
import contextlib
import os
import tempfile

from . import _swell

_DECLARATIONS = ("frequency_unit", "density_unit", "direction_convention", "direction_unit")


def _is_data_array(value):
    return type(value).__name__ == "DataArray" and hasattr(value, "dims")


def _table_spec(spec, folder, count):
    """A [spectrum] table whose file is a DataArray, with the file written into `folder`."""
    array = spec["file"]
    out = {key: value for key, value in spec.items() if key != "file"}
    out.setdefault("model", "table")
    for key in _DECLARATIONS + ("select",):
        if key not in out and key in array.attrs:
            out[key] = array.attrs[key]
    name = array.name or "efth"
    out.setdefault("variable", name)
    if len(array.dims) < 2:
        raise _swell.InvalidInput(f"[spectrum] file: a DataArray of dims {array.dims}; a table "
                                  f"takes efth(freq, dir)")
    for key, default in (("frequency_variable", "freq"), ("direction_variable", "dir")):
        if key not in out:
            if default not in array.dims:
                raise _swell.InvalidInput(
                    f"[spectrum] {key}: the DataArray's dims {array.dims} have no '{default}'; "
                    f"name the dimension with {key} = \"…\"")
            out[key] = default
    path = os.path.join(folder, f"table{count}.nc")
    attrs = {k: v for k, v in array.attrs.items() if isinstance(v, (str, int, float))}
    array.copy().assign_attrs(attrs).rename(name).to_dataset().to_netcdf(path)
    out["file"] = path
    return out


def _copied(node):
    """Dicts and lists copied all the way down, so that the caller's sections stay untouched;
    the values themselves (a DataArray too) are shared."""
    if isinstance(node, dict):
        return {key: _copied(value) for key, value in node.items()}
    if isinstance(node, list):
        return [_copied(item) for item in node]
    return node


@contextlib.contextmanager
def with_tables(sections):
    """`sections` (copied) with every DataArray table written out; the files live while the
    block runs. A table may sit in [spectrum], in a composite sea's [[spectrum]] list and in a
    cascade's [cascade.spectrum]."""
    sections = _copied(sections)
    found = []

    def visit(node):
        if isinstance(node, dict):
            if _is_data_array(node.get("file")):
                found.append(node)
            for key, value in node.items():
                if key == "spectrum" and _is_data_array(value):
                    node[key] = value = {"model": "table", "file": value}
                visit(value)
        elif isinstance(node, list):
            for item in node:
                visit(item)

    visit(sections)
    if not found:
        yield sections
        return
    with tempfile.TemporaryDirectory(prefix="swell-table-") as folder:
        for count, spec in enumerate(found):
            replacement = _table_spec(spec, folder, count)
            spec.clear()
            spec.update(replacement)
        yield sections
