#pragma once
// Keyword arguments onto an options struct: `plmap.project(s1, s2, max_distance=0.1)` sets
// ProjectionOptions::max_distance. Each struct lists its fields once, as (name, setter) pairs;
// an unknown name is a TypeError naming it (as Python's own calls do), a value of the wrong
// type a TypeError naming the field and the type it expects.

#include <plmap/core/projection_rules.hpp>

#include <pybind11/pybind11.h>

#include <functional>
#include <map>
#include <string>

namespace plmap::python {

namespace py = pybind11;

template <class Options>
struct KeywordField {
  std::string expected;  ///< "float", "bool", ... for the error message
  std::function<void(Options&, py::handle)> set;
};

template <class Options>
using KeywordFields = std::map<std::string, KeywordField<Options>, std::less<>>;

/// A field set by py::cast<T>; bool fields accept only True/False (pybind11 does not convert
/// numbers to bool without asking).
template <class T, class Options>
KeywordField<Options> keyword_field(T Options::*member, std::string expected) {
  return {std::move(expected), [member](Options& o, py::handle value) { o.*member = py::cast<T>(value); }};
}

/// The normal check a str argument names; ValueError naming `function` and the valid names
/// for any other (project() and Map.check_against_rays() take the same names).
inline NormalCheck normal_check_argument(const std::string& function, const std::string& name) {
  if (const auto check = normal_check_from_name(name)) return *check;
  throw py::value_error(function + "(): normal_check must be 'none', 'facing' or 'aligned', got '" + name + "'");
}

template <class Options>
void apply_keyword_options(const std::string& function, const py::kwargs& kwargs,
                           const KeywordFields<Options>& fields, Options& options) {
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::cast<std::string>(key);
    const auto field = fields.find(name);
    if (field == fields.end()) {
      std::string valid;
      for (const auto& [known, unused] : fields) valid += (valid.empty() ? "" : ", ") + known;
      throw py::type_error(function + "() got an unexpected keyword argument '" + name +
                           "' (valid: " + valid + ")");
    }
    try {
      field->second.set(options, value);
    } catch (const py::cast_error&) {
      throw py::type_error(function + "(): keyword argument '" + name + "' expects " +
                           field->second.expected + ", got " +
                           py::cast<std::string>(py::str(py::type::of(value).attr("__name__"))));
    }
  }
}

}  // namespace plmap::python
