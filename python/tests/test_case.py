"""swell.Case from a path, TOML text and a dict: the same case, the command's messages."""
import numpy as np
import pytest

import swell
from conftest import REPOSITORY, command_error


def test_path_text_and_dict_read_the_same_case(tmp_path, sea):
    from_dict = swell.Case(sea)
    path = tmp_path / "case.toml"
    path.write_text(from_dict.to_toml())
    from_path = swell.Case(path)
    from_text = swell.Case(path.read_text())
    assert from_path.to_toml() == from_dict.to_toml() == from_text.to_toml()
    assert from_dict.n == (64, 64) and from_dict.length == (200.0, 200.0)
    np.testing.assert_array_equal(from_dict.times, [0.0, 0.5, 1.0, 1.5])
    assert from_path.origin == str(path) and from_dict.origin == ""
    assert from_dict.kind == "grid"


def test_numpy_values_in_a_dict_are_their_python_values(sea):
    sea["grid"]["n"] = np.array([64, 64])
    sea["spectrum"]["hs"] = np.float32(3.0)
    sea["time"]["frames"] = np.int64(4)
    assert swell.Case(sea).to_toml() == swell.Case(
        dict(sea, grid={"n": [64, 64], "length": [200.0, 200.0]},
             spectrum=dict(sea["spectrum"], hs=3.0), time=dict(sea["time"], frames=4))).to_toml()


def test_bad_case_raises_the_commands_message_without_file_and_line(tmp_path, sea):
    sea["grid"]["n"] = [64, -2]
    path = tmp_path / "bad.toml"
    with pytest.raises(swell.InvalidInput) as from_dict:
        swell.Case(sea)
    assert isinstance(from_dict.value, ValueError)
    # The command's message for the same file, less its "FILE:LINE: " prefix.
    text = "\n".join(f"[{name}]\n" + "\n".join(f"{k} = {v!r}".replace("'", '"').replace("True", "true")
                                              for k, v in section.items())
                     for name, section in sea.items())
    path.write_text(text)
    expected = command_error("gate", "--power", "--case", path)
    prefix = f"{path}:"
    assert expected.startswith(prefix)
    assert expected.split(": ", 1)[1] == str(from_dict.value)
    with pytest.raises(ValueError) as from_path:
        swell.Case(path)
    assert str(from_path.value) == expected


def test_unknown_key_and_wrong_types_are_named():
    with pytest.raises(ValueError, match="grid"):
        swell.Case({"grid": {"n": [64, 64], "length": [1.0, 1.0], "bogus": 1}})
    with pytest.raises(ValueError, match=r"\[grid\] n.*has no TOML value"):
        swell.Case({"grid": {"n": None}})
    with pytest.raises(ValueError, match="no such case file"):
        swell.Case("/nonexistent/case.toml")
    with pytest.raises(ValueError):
        swell.Case(3.5)


def test_shipped_cases_read():
    for path in sorted((REPOSITORY / "data" / "cases").glob("*.toml")):
        case = swell.Case(path)
        assert case.describe()
