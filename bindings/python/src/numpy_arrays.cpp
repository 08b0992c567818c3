#include "numpy_arrays.hpp"

namespace plmap::python {

namespace {

std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

void require_shape(const py::array& a, const std::string& name, py::ssize_t columns) {
  const bool ok = columns == 0 ? a.ndim() == 1 : a.ndim() == 2 && (columns < 0 || a.shape(1) == columns);
  if (ok) return;
  const std::string expected = columns == 0  ? "(n,)"
                               : columns < 0 ? "(n, k)"
                                             : "(n, " + std::to_string(columns) + ")";
  throw py::value_error(name + ": expected shape " + expected + ", got " + shape_text(a));
}

}  // namespace

py::array_t<double> float_matrix(py::handle value, const std::string& name, py::ssize_t columns) {
  auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
  if (!a) throw py::type_error(name + ": expected an array of numbers");
  require_shape(a, name, columns);
  return a;
}

py::array_t<std::int64_t> index_matrix(py::handle value, const std::string& name, py::ssize_t columns) {
  auto raw = py::array::ensure(value);
  if (!raw) throw py::type_error(name + ": expected an array of integers");
  const char kind = raw.dtype().kind();
  if (kind != 'i' && kind != 'u' && !(raw.size() == 0))
    throw py::type_error(name + ": expected an integer array, got dtype " +
                         py::cast<std::string>(py::str(raw.dtype())));
  auto a = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(raw);
  if (raw.size() == 0 && columns > 0 && raw.ndim() == 1)  // [] for no elements
    a = py::array_t<std::int64_t>(std::vector<py::ssize_t>{0, columns});
  require_shape(a, name, columns);
  return a;
}

}  // namespace plmap::python
