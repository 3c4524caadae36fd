#include "config_values.h"

#include <cmath>
#include <string>

namespace py = pybind11;

namespace bsg::python {
namespace {

std::string type_name(py::handle value) { return py::str(py::type::handle_of(value).attr("__name__")); }

YAML::Node yaml_value(py::handle value, const std::string& where) {
  if (value.is_none()) return YAML::Node(YAML::NodeType::Null);
  if (py::isinstance<py::bool_>(value)) return YAML::Node(value.cast<bool>() ? "true" : "false");
  if (py::isinstance<py::str>(value)) {
    YAML::Node text(value.cast<std::string>());
    text.SetTag("!");  // quoted text, as 'value' in a YAML file: a string, never a number
    return text;
  }
  if (py::isinstance<py::float_>(value)) {
    const double number = value.cast<double>();
    if (std::isnan(number)) return YAML::Node(".nan");
    if (std::isinf(number)) return YAML::Node(number > 0 ? ".inf" : "-.inf");
    return YAML::Node(py::repr(value).cast<std::string>());  // the shortest text that reads back
  }
  if (py::hasattr(value, "__index__")) {  // int and NumPy's integers
    return YAML::Node(py::str(py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr()))).cast<std::string>());
  }
  if (py::hasattr(value, "__float__") && !py::isinstance<py::sequence>(value)) {  // NumPy's floats
    return yaml_value(py::float_(py::reinterpret_borrow<py::object>(value)), where);
  }
  if (py::isinstance<py::dict>(value)) {
    YAML::Node mapping(YAML::NodeType::Map);
    for (const auto& [key, item] : py::reinterpret_borrow<py::dict>(value)) {
      if (!py::isinstance<py::str>(key)) {
        throw py::type_error(where + ": a key must be a str, got " + type_name(key));
      }
      const std::string name = key.cast<std::string>();
      mapping[name] = yaml_value(item, where + "['" + name + "']");
    }
    return mapping;
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    YAML::Node sequence(YAML::NodeType::Sequence);
    std::size_t index = 0;
    for (const py::handle item : value) {
      sequence.push_back(yaml_value(item, where + "[" + std::to_string(index++) + "]"));
    }
    return sequence;
  }
  throw py::type_error(where + ": a value of type " + type_name(value) +
                       " is not a configuration value (bool, int, float, str, list, dict or None)");
}

}  // namespace

std::vector<ConfigEntry> config_entries_from_dict(py::handle values, const std::string& what,
                                                  const std::function<std::string(const std::string&)>& origin_of) {
  if (!py::isinstance<py::dict>(values)) {
    throw py::type_error(what + " must be a dict of key -> value, got " + type_name(values));
  }
  std::vector<ConfigEntry> entries;
  for (const auto& [key, value] : py::reinterpret_borrow<py::dict>(values)) {
    if (!py::isinstance<py::str>(key)) {
      throw py::type_error(what + ": a key must be a str, got " + type_name(key));
    }
    const std::string name = key.cast<std::string>();
    const std::string origin = origin_of(name);
    entries.push_back(make_config_entry(name, yaml_value(value, origin), origin));
  }
  return entries;
}

}  // namespace bsg::python
