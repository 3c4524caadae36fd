#include "action_input.h"

#include <algorithm>
#include <stdexcept>

namespace py = pybind11;

namespace bsg::python {

std::string shape_text(std::span<const py::ssize_t> shape) {
  std::string text = "(";
  for (size_t k = 0; k < shape.size(); ++k) {
    if (k > 0) text += ", ";
    text += std::to_string(shape[k]);
  }
  return text + (shape.size() == 1 ? ",)" : ")");
}

namespace {

[[noreturn]] void raise_value_error(const std::string& problem,
                                    std::span<const py::ssize_t> shape) {
  throw py::value_error("action " + problem + ": expected a float array of shape " +
                        shape_text(shape));
}

}  // namespace

std::span<const double> action_values(py::handle action, std::span<const py::ssize_t> shape,
                                      std::vector<double>& scratch) {
  // Fast path: the float64 C-contiguous array a numpy user passes, checked on
  // numpy's struct directly (pybind11's isinstance<array_t> builds a dtype).
  using py::detail::npy_api;
  constexpr int kDirectFlags = npy_api::NPY_ARRAY_C_CONTIGUOUS_ | npy_api::NPY_ARRAY_ALIGNED_;
  const auto* proxy = py::detail::array_proxy(action.ptr());
  if (npy_api::get().PyArray_Check_(action.ptr()) &&
      py::detail::array_descriptor_proxy(proxy->descr)->type_num == npy_api::NPY_DOUBLE_ &&
      py::detail::array_descriptor_proxy(proxy->descr)->byteorder != '>' &&
      (proxy->flags & kDirectFlags) == kDirectFlags) {
    const auto array = py::reinterpret_borrow<py::array>(action);
    if (array.ndim() != static_cast<py::ssize_t>(shape.size()) ||
        !std::equal(shape.begin(), shape.end(), array.shape())) {
      raise_value_error("has shape " +
                            shape_text({array.shape(), static_cast<size_t>(array.ndim())}),
                        shape);
    }
    return {static_cast<const double*>(array.data()), static_cast<size_t>(array.size())};
  }
  const py::array array = py::array::ensure(action);  // empty (error cleared) if not array-like
  if (!array) {
    raise_value_error("is not array-like (" + std::string(py::str(action.get_type())) + ")",
                      shape);
  }
  const char kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u') {
    raise_value_error("has dtype " + std::string(py::str(array.dtype())), shape);
  }
  if (array.ndim() != static_cast<py::ssize_t>(shape.size()) ||
      !std::equal(shape.begin(), shape.end(), array.shape())) {
    raise_value_error(
        "has shape " + shape_text({array.shape(), static_cast<size_t>(array.ndim())}), shape);
  }
  const auto converted =
      py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  if (!converted) raise_value_error("cannot be converted to float64", shape);
  scratch.assign(converted.data(), converted.data() + converted.size());
  return scratch;
}

void raise_invalid_action(const std::invalid_argument& error,
                          std::span<const py::ssize_t> shape) {
  throw py::value_error(std::string(error.what()) + ": expected a finite float array of shape " +
                        shape_text(shape));
}

}  // namespace bsg::python
