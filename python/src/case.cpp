// swell.Case: a case file from a path, a TOML string or a dict of its sections. A dict becomes
// TOML through toml++ (the case-file reader's own library) and is then read by the same
// parse_case_toml as a file, so every rule and message is the command's; a case with no file
// has no file:line prefix in its messages.
#include <fmt/format.h>
#include <pybind11/stl.h>

#include <sstream>
#include <toml++/toml.h>

#include "bindings.hpp"
#include "swell/reference/errors.hpp"

namespace swell::python {
namespace {

toml::table table_of(const py::dict& dict, const std::string& where);

// A TOML value of a plain Python value (swell/__init__.py has turned NumPy scalars and arrays
// into Python ones); `where` names the key in messages ("[grid] n").
std::unique_ptr<toml::node> node_of(const py::handle& value, const std::string& where) {
  if (py::isinstance<py::bool_>(value)) return std::make_unique<toml::value<bool>>(value.cast<bool>());
  if (py::isinstance<py::int_>(value)) {
    try {
      return std::make_unique<toml::value<int64_t>>(value.cast<int64_t>());
    } catch (const py::cast_error&) {
      throw InvalidInput(fmt::format("{}: {} does not fit a 64-bit integer", where,
                                     std::string(py::repr(value))));
    }
  }
  if (py::isinstance<py::float_>(value)) return std::make_unique<toml::value<double>>(value.cast<double>());
  if (py::isinstance<py::str>(value)) return std::make_unique<toml::value<std::string>>(value.cast<std::string>());
  if (py::isinstance<py::dict>(value)) {
    return std::make_unique<toml::table>(table_of(value.cast<py::dict>(), where));
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    auto array = std::make_unique<toml::array>();
    std::size_t i = 0;
    for (const auto& item : value) {
      auto node = node_of(item, fmt::format("{}[{}]", where, i++));
      array->push_back(std::move(*node));
    }
    return array;
  }
  throw InvalidInput(fmt::format("{}: a {} has no TOML value (give a number, a string, a bool, a "
                                 "list or a dict)",
                                 where, std::string(py::str(value.get_type().attr("__name__")))));
}

toml::table table_of(const py::dict& dict, const std::string& where) {
  toml::table table;
  for (const auto& [key, value] : dict) {
    if (!py::isinstance<py::str>(key)) {
      throw InvalidInput(fmt::format("{}: key {} is not a string", where.empty() ? "the case" : where,
                                     std::string(py::repr(key))));
    }
    const auto name = key.cast<std::string>();
    const std::string here = where.empty() ? "[" + name + "]" : where + " " + name;
    auto node = node_of(value, here);
    table.insert_or_assign(name, std::move(*node));
  }
  return table;
}

Case case_from_path(const std::string& path) {
  return {std::make_shared<const validation::CaseFile>(validation::read_case_file(path))};
}

Case case_from_toml(const std::string& text) {
  return {std::make_shared<const validation::CaseFile>(validation::parse_case_toml(text, ""))};
}

Case case_from_dict(const py::dict& sections) {
  std::ostringstream text;
  text << table_of(sections, "");
  return case_from_toml(text.str());
}

std::string kind_of(const validation::CaseFile& c) {
  if (c.is_probe_case()) return "probes";
  if (c.is_cascade_set()) return "cascades";
  return c.ocean.is_lattice() ? "lattice" : "grid";
}

}  // namespace

void bind_case(py::module_& m) {
  py::class_<Case>(m, "Case")
      .def_static("from_path", &case_from_path)
      .def_static("from_toml", &case_from_toml)
      .def_static("from_dict", &case_from_dict)
      .def_property_readonly("kind", [](const Case& c) { return kind_of(*c.file); })
      .def_property_readonly("origin", [](const Case& c) { return c.file->origin.string(); })
      .def_property_readonly("frames", [](const Case& c) { return c.file->ocean.frames; })
      .def_property_readonly("n", [](const Case& c) {
        const auto& o = c.file->ocean;
        return o.is_lattice() ? std::vector<std::int64_t>{o.lattice->points()}
                              : std::vector<std::int64_t>{o.grid.nx, o.grid.ny};
      })
      .def_property_readonly("length", [](const Case& c) {
        return std::vector<double>{c.file->ocean.grid.lx, c.file->ocean.grid.ly};
      })
      .def_property_readonly("times", [](const Case& c) {
        std::vector<double> times;
        for (int f = 0; f < c.file->ocean.frames; ++f) times.push_back(c.file->ocean.time(f));
        return times;
      })
      .def_property_readonly("cascades", [](const Case& c) { return c.file->cascades.size(); })
      .def_property_readonly("probes", [](const Case& c) {
        return c.file->is_probe_case() ? c.file->probes->layout.positions.size() : std::size_t(0);
      })
      .def_property_readonly("samples", [](const Case& c) {
        return c.file->is_probe_case() ? c.file->probes->layout.samples : std::size_t(0);
      })
      .def_property_readonly("precision", [](const Case& c) { return c.file->input.precision; })
      .def("describe", [](const Case& c) {
        return c.file->is_probe_case() ? c.file->probe_case().describe() : c.file->ocean.describe();
      })
      .def("to_toml", [](const Case& c) { return validation::case_toml(*c.file); });
}

}  // namespace swell::python
