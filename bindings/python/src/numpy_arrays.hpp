#pragma once
// Checked conversions of Python arguments to numpy arrays of a fixed dtype and shape, with errors
// that name the argument and the shape that was expected.

#include <pybind11/numpy.h>

#include <cstdint>
#include <vector>
#include <string>

namespace plmap::python {

namespace py = pybind11;

/// A C-contiguous float64 array of shape (n, columns) (columns = -1: any). Numbers of other
/// dtypes are converted; anything else is a TypeError.
py::array_t<double> float_matrix(py::handle value, const std::string& name, py::ssize_t columns);

/// A C-contiguous int64 array of shape (n, columns) (columns = -1: any; 0: one-dimensional
/// (n,)). Only integer dtypes are accepted (a float array of indices is a TypeError rather than
/// silently truncated); an empty list is fine.
py::array_t<std::int64_t> index_matrix(py::handle value, const std::string& name, py::ssize_t columns);

}  // namespace plmap::python
