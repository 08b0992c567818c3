# The Python interpreter of the build, and whether the Python module (bindings/python) is built.
#
# The module is compiled against Debian's pybind11 and tested with Debian's numpy, pytest and
# scipy (scripts/setup-debian installs them). Those belong to the system interpreter
# /usr/bin/python3; another python3 earlier in PATH (pyenv, a virtual environment) lacks them or
# has another ABI. So the system interpreter is the default when it exists, for everything the
# build runs in Python (the CLI tests too). Choose another with -DPython3_EXECUTABLE=/path/python3;
# its numpy (and pytest, scipy for the tests) are then yours to provide.
#
# Sets PLMAP_PYTHON_MODULE to ON when the module can be built.
if(NOT Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
  set(Python3_EXECUTABLE /usr/bin/python3 CACHE FILEPATH
      "The Python interpreter the build uses (CLI tests, the Python module and its tests)")
endif()
# FindPython keeps the interpreter an earlier configure found (its internal cache entry) even
# when Python3_EXECUTABLE names another: forget it, so that the named one is used.
if(Python3_EXECUTABLE AND DEFINED CACHE{_Python3_EXECUTABLE}
   AND NOT "${_Python3_EXECUTABLE}" STREQUAL "${Python3_EXECUTABLE}")
  unset(_Python3_EXECUTABLE CACHE)
endif()

set(PLMAP_PYTHON_MODULE OFF)
if(NOT PLMAP_BUILD_PYTHON)
  return()
endif()
if(PLMAP_SANITIZE)
  # An extension instrumented with AddressSanitizer only loads into an interpreter started with
  # libasan preloaded (LD_PRELOAD), and then reports CPython's own allocations: not worth it.
  # The sanitizer build runs the C++ suite; the Python tests run in the normal build.
  message(STATUS "Python module: not built with PLMAP_SANITIZE=ON")
  return()
endif()

find_package(Python3 COMPONENTS Interpreter Development.Module)
if(NOT Python3_Interpreter_FOUND OR NOT Python3_Development.Module_FOUND)
  message(STATUS "Python module: skipped, no Python 3 interpreter with headers "
                 "(Debian: python3-dev)")
  return()
endif()
find_package(pybind11 CONFIG QUIET)
if(NOT pybind11_FOUND)
  message(STATUS "Python module: skipped, pybind11 not found (Debian: pybind11-dev)")
  return()
endif()
execute_process(COMMAND ${Python3_EXECUTABLE} -c "import numpy"
                RESULT_VARIABLE _plmap_numpy_missing OUTPUT_QUIET ERROR_QUIET)
if(_plmap_numpy_missing)
  message(WARNING "Python module: skipped, ${Python3_EXECUTABLE} cannot import numpy "
                  "(Debian: python3-numpy; or choose another -DPython3_EXECUTABLE)")
  return()
endif()
set(PLMAP_PYTHON_MODULE ON)
message(STATUS "Python module: built for ${Python3_EXECUTABLE} (Python ${Python3_VERSION}, "
               "pybind11 ${pybind11_VERSION})")
