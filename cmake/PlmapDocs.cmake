# The `docs` target: HTML API reference generated with Doxygen (Debian package `doxygen`) into
# <build>/docs/api from the public headers of every library folder and the pages docs/*.md.
# Without Doxygen the target does not exist and the rest of the build is unaffected.
#
# This file also runs in script mode (cmake -P) as the last step of the target: it prints the
# warnings Doxygen logged and fails when they contain errors (or any warning, with
# PLMAP_DOCS_WARNINGS_AS_ERRORS=ON).

if(CMAKE_SCRIPT_MODE_FILE)
  # cmake -DLOG=<warning log> -DSTRICT=<ON|OFF> -P PlmapDocs.cmake
  set(_text "")
  if(EXISTS "${LOG}")
    file(READ "${LOG}" _text)
  endif()
  string(STRIP "${_text}" _text)
  if(_text STREQUAL "")
    message(STATUS "docs: Doxygen reported no warnings")
    return()
  endif()
  string(REGEX MATCHALL "[^\n]*(warning|error):[^\n]*" _lines "${_text}")
  list(LENGTH _lines _count)
  string(REGEX MATCHALL "[^\n]*error:[^\n]*" _errors "${_text}")
  list(LENGTH _errors _error_count)
  message("${_text}")
  if(_error_count GREATER 0 OR STRICT)
    message(FATAL_ERROR "docs: Doxygen reported ${_count} problems (${_error_count} errors); see ${LOG}")
  endif()
  message(STATUS "docs: Doxygen reported ${_count} warnings; see ${LOG}")
  return()
endif()

option(PLMAP_DOCS_WARNINGS_AS_ERRORS "Fail the docs target on any Doxygen warning" OFF)

find_package(Doxygen QUIET OPTIONAL_COMPONENTS dot)
if(NOT DOXYGEN_FOUND)
  message(STATUS "Doxygen not found: no `docs` target (install the Debian package doxygen)")
  return()
endif()

set(PLMAP_DOCS_OUTPUT_DIR "${PROJECT_BINARY_DIR}/docs")
set(PLMAP_DOCS_WARNING_LOG "${PLMAP_DOCS_OUTPUT_DIR}/doxygen-warnings.log")

set(_plmap_doc_include_dirs "")
foreach(_folder core strategies verify solvers construct)
  if(IS_DIRECTORY "${PROJECT_SOURCE_DIR}/${_folder}/include")
    list(APPEND _plmap_doc_include_dirs "${PROJECT_SOURCE_DIR}/${_folder}/include")
  endif()
endforeach()

# The main page: the README when there is one, otherwise a short generated page.
if(EXISTS "${PROJECT_SOURCE_DIR}/README.md")
  set(PLMAP_DOXYGEN_MAINPAGE "${PROJECT_SOURCE_DIR}/README.md")
else()
  set(PLMAP_DOXYGEN_MAINPAGE "${PLMAP_DOCS_OUTPUT_DIR}/mainpage.md")
  file(WRITE "${PLMAP_DOXYGEN_MAINPAGE}"
       "# plmap API reference\n\n${PROJECT_DESCRIPTION}, version ${PROJECT_VERSION}.\n\n"
       "The classes and functions are listed under *Namespaces* and *Files*; the guides are "
       "under *Related Pages*.\n")
endif()

set(_plmap_doc_inputs ${_plmap_doc_include_dirs} "${PROJECT_SOURCE_DIR}/docs" "${PLMAP_DOXYGEN_MAINPAGE}")
list(REMOVE_DUPLICATES _plmap_doc_inputs)
set(PLMAP_DOXYGEN_INPUT "")
foreach(_input IN LISTS _plmap_doc_inputs)
  string(APPEND PLMAP_DOXYGEN_INPUT " \"${_input}\"")
endforeach()
set(PLMAP_DOXYGEN_INCLUDE_DIRS "")
foreach(_dir IN LISTS _plmap_doc_include_dirs)
  string(APPEND PLMAP_DOXYGEN_INCLUDE_DIRS " \"${_dir}\"")
endforeach()
set(PLMAP_DOXYGEN_IMAGE_PATH "\"${PROJECT_SOURCE_DIR}/docs\"")
if(TARGET Doxygen::dot)
  set(PLMAP_DOXYGEN_HAVE_DOT YES)
  get_target_property(_dot Doxygen::dot IMPORTED_LOCATION)
  get_filename_component(PLMAP_DOXYGEN_DOT_PATH "${_dot}" DIRECTORY)
else()
  set(PLMAP_DOXYGEN_HAVE_DOT NO)
  set(PLMAP_DOXYGEN_DOT_PATH "")
endif()

configure_file("${PROJECT_SOURCE_DIR}/docs/Doxyfile.in" "${PLMAP_DOCS_OUTPUT_DIR}/Doxyfile" @ONLY)

add_custom_target(docs
  COMMAND ${CMAKE_COMMAND} -E remove -f "${PLMAP_DOCS_WARNING_LOG}"
  COMMAND Doxygen::doxygen "${PLMAP_DOCS_OUTPUT_DIR}/Doxyfile"
  COMMAND ${CMAKE_COMMAND} -DLOG=${PLMAP_DOCS_WARNING_LOG} -DSTRICT=${PLMAP_DOCS_WARNINGS_AS_ERRORS}
          -P "${CMAKE_CURRENT_LIST_FILE}"
  WORKING_DIRECTORY "${PROJECT_SOURCE_DIR}"
  COMMENT "API reference with Doxygen -> ${PLMAP_DOCS_OUTPUT_DIR}/api/index.html"
  VERBATIM)
