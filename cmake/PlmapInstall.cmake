# Installation: headers, libraries, the `plmap` tool, a CMake package (find_package(plmap) giving
# plmap::core, plmap::strategies, plmap::verify, ...) and a pkg-config file.
#
# Included at the end of the top-level CMakeLists.txt, after every library folder was added, so
# that the targets and their link interfaces are complete. The set of libraries is discovered
# (every plmap_* library defined in a library folder), and the packages the installed config must
# re-find are derived from the targets' link interfaces, so a library or dependency added later
# is installed without touching this file -- unless it is a dependency this file does not know
# yet, which is reported with a warning naming it.

include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(PLMAP_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/plmap"
    CACHE STRING "Where plmapConfig.cmake is installed (relative to the prefix)")
set(PLMAP_INSTALL_PKGCONFIGDIR "${CMAKE_INSTALL_LIBDIR}/pkgconfig"
    CACHE STRING "Where plmap.pc is installed (relative to the prefix)")

# ---- which libraries ----------------------------------------------------------------------------
# The library folders, in dependency order. A folder counts once it has been add_subdirectory'd;
# each plmap_* library target it defines is installed (static, shared or header-only).
set(_plmap_library_folders core strategies verify solvers construct)
get_property(_plmap_added_dirs DIRECTORY "${PROJECT_SOURCE_DIR}" PROPERTY SUBDIRECTORIES)

set(_plmap_libraries "")          # target names
set(_plmap_header_dirs "")        # <folder>/include of the folders that have a library
foreach(_folder IN LISTS _plmap_library_folders)
  set(_dir "${PROJECT_SOURCE_DIR}/${_folder}")
  if(NOT _dir IN_LIST _plmap_added_dirs)
    continue()
  endif()
  get_property(_dir_targets DIRECTORY "${_dir}" PROPERTY BUILDSYSTEM_TARGETS)
  set(_folder_has_library FALSE)
  foreach(_t IN LISTS _dir_targets)
    get_target_property(_type ${_t} TYPE)
    if(_t MATCHES "^plmap_" AND _type MATCHES "^(STATIC|SHARED|INTERFACE)_LIBRARY$")
      list(APPEND _plmap_libraries ${_t})
      set(_folder_has_library TRUE)
    endif()
  endforeach()
  if(_folder_has_library AND IS_DIRECTORY "${_dir}/include")
    list(APPEND _plmap_header_dirs "${_dir}/include")
  endif()
endforeach()

# ---- what the libraries link --------------------------------------------------------------------
# Reads INTERFACE_LINK_LIBRARIES: for a static library it holds the PUBLIC items and, wrapped in
# $<LINK_ONLY:...>, the PRIVATE ones (consumers must link them too); for a shared library only
# the PUBLIC ones. Sets, in the caller:
#   <out>_internal  plmap libraries this one links
#   <out>_imported  imported targets (external packages), each suffixed "|public" or "|private"
#   <out>_plain     plain library names / flags ("m", "-pthread"), suffixed likewise
function(_plmap_link_items target out)
  set(internal "")
  set(imported "")
  set(plain "")
  get_target_property(items ${target} INTERFACE_LINK_LIBRARIES)
  if(NOT items)
    set(items "")
  endif()
  foreach(item IN LISTS items)
    if(item MATCHES "^::@")  # directory markers of target_link_libraries from another folder
      continue()
    endif()
    set(visibility public)
    if(item MATCHES "^\\$<LINK_ONLY:(.*)>$")
      set(item "${CMAKE_MATCH_1}")
      set(visibility private)
    endif()
    if(item MATCHES "^\\$<BUILD_INTERFACE:.*>$")
      continue()  # build-only (e.g. plmap_compile_options): never reaches consumers
    endif()
    if(item MATCHES "^\\$<INSTALL_INTERFACE:(.*)>$")
      set(item "${CMAKE_MATCH_1}")
    endif()
    if(item MATCHES "\\$<")
      message(WARNING "plmap install: ${target} links '${item}'; this generator expression is "
                      "not understood by cmake/PlmapInstall.cmake, so its package is not re-found")
      continue()
    endif()
    # Imported targets found inside a library folder (find_package there) are invisible here,
    # so a name that is not a target may still be one: such names are recognised by
    # _plmap_package_of below, by name.
    if(TARGET ${item})
      # Aliases (plmap::core, CGAL::CGAL) are resolved to decide what the target is, but an
      # imported target keeps the name the library used, which identifies its package.
      set(real ${item})
      get_target_property(aliased ${item} ALIASED_TARGET)
      if(aliased)
        set(real ${aliased})
      endif()
      get_target_property(is_imported ${real} IMPORTED)
      if(is_imported)
        list(APPEND imported "${item}|${visibility}")
      elseif(real IN_LIST _plmap_libraries)
        list(APPEND internal ${real})
      else()
        message(FATAL_ERROR
          "plmap install: ${target} links the build-only target '${real}' in its link interface, "
          "so installed consumers could not link it. Wrap it in $<BUILD_INTERFACE:...> or make it "
          "one of the installed plmap_* libraries.")
      endif()
    elseif(item MATCHES "::")
      list(APPEND imported "${item}|${visibility}")
    else()
      list(APPEND plain "${item}|${visibility}")
    endif()
  endforeach()
  set(${out}_internal ${internal} PARENT_SCOPE)
  set(${out}_imported ${imported} PARENT_SCOPE)
  set(${out}_plain ${plain} PARENT_SCOPE)
endfunction()

# Maps an imported target to how a consumer gets it: the find_dependency() arguments for the CMake
# package, and the pkg-config modules / linker flags for plmap.pc. Sets <out>_find, <out>_pc,
# <out>_libs in the caller (empty when nothing is needed). With quiet = TRUE an unknown name is
# not reported (it may be a plain system library such as "m").
function(_plmap_package_of imported out quiet)
  set(find "")
  set(pc "")
  set(libs "")
  if(imported MATCHES "^Eigen3::")
    set(find "Eigen3 3.4 NO_MODULE")
    set(pc eigen3)
  elseif(imported MATCHES "^Threads::")
    set(find "Threads")
    set(libs "-pthread")
  elseif(imported MATCHES "^fmt::")
    set(find "fmt")
    set(pc fmt)
  elseif(imported MATCHES "^CGAL::")
    set(find "CGAL")
    set(pc gmp mpfr)  # header-only CGAL; its exact number types come from GMP/MPFR
  elseif(imported MATCHES "^TBB::")
    set(find "TBB")
    set(pc tbb)
  elseif(imported MATCHES "^ZLIB::")
    set(find "ZLIB")
    set(pc zlib)  # the binary map format's CRC-32
  elseif(imported MATCHES "^nlohmann_json::")
    set(find "nlohmann_json")
    set(pc nlohmann_json)
  elseif(imported MATCHES "^rapidcheck(_.*)?$")
    set(find "rapidcheck")
    set(libs "-lrapidcheck")  # Debian ships no rapidcheck.pc
  elseif(imported MATCHES "^Ceres::" OR imported STREQUAL "ceres" OR imported STREQUAL "Ceres::ceres")
    set(find "Ceres")
    set(libs "-lceres")  # no ceres.pc; libceres.so brings its own dependencies
  elseif(imported MATCHES "^nanoflann::")
    set(find "nanoflann")
    set(pc nanoflann)
  elseif(imported MATCHES "^CLI11::")
    set(find "CLI11")
  elseif(imported MATCHES "^tomlplusplus::")
    set(find "tomlplusplus")
    set(pc tomlplusplus)
  elseif(imported MATCHES "^PkgConfig::(.+)$")
    # Found with pkg_check_modules(<PREFIX> IMPORTED_TARGET <module>); by the project's
    # convention the prefix is the module name.
    set(find "PkgConfig-module ${CMAKE_MATCH_1}")
    set(pc ${CMAKE_MATCH_1})
  elseif(NOT quiet)
    message(WARNING "plmap install: unknown imported target '${imported}' in the link interface "
                    "of an installed library; add it to _plmap_package_of in "
                    "cmake/PlmapInstall.cmake so that plmapConfig.cmake re-finds it")
  endif()
  set(${out}_find "${find}" PARENT_SCOPE)
  set(${out}_pc "${pc}" PARENT_SCOPE)
  set(${out}_libs "${libs}" PARENT_SCOPE)
endfunction()

set(_plmap_find_dependencies "")  # one entry per package, in first-seen order
set(_plmap_pc_requires "")
set(_plmap_pc_requires_private "")
set(_plmap_pc_libs_extra "")
set(_plmap_pc_libs_private "")
set(_plmap_components "")
foreach(_t IN LISTS _plmap_libraries)
  _plmap_link_items(${_t} _links)
  set(_plmap_internal_deps_${_t} ${_links_internal})
  foreach(_entry IN LISTS _links_imported _links_plain)
    string(REPLACE "|" ";" _pair "${_entry}")
    list(GET _pair 0 _item)
    list(GET _pair 1 _visibility)
    set(_quiet TRUE)
    if(_entry IN_LIST _links_imported)
      set(_quiet FALSE)
    endif()
    _plmap_package_of(${_item} _pkg ${_quiet})
    if(_pkg_find)
      list(APPEND _plmap_find_dependencies "${_pkg_find}")
    elseif(NOT _entry IN_LIST _links_imported)
      # a plain library name or linker flag
      set(_pkg_pc "")
      if(_item MATCHES "^-" OR IS_ABSOLUTE "${_item}")
        set(_pkg_libs "${_item}")
      else()
        set(_pkg_libs "-l${_item}")
      endif()
    endif()
    # A shared libplmap carries its private dependencies itself; a static one needs them on the
    # consumer's link line, so for pkg-config they are then ordinary requirements.
    if(_visibility STREQUAL "private" AND BUILD_SHARED_LIBS)
      list(APPEND _plmap_pc_requires_private ${_pkg_pc})
      list(APPEND _plmap_pc_libs_private ${_pkg_libs})
    else()
      list(APPEND _plmap_pc_requires ${_pkg_pc})
      list(APPEND _plmap_pc_libs_extra ${_pkg_libs})
    endif()
  endforeach()
  get_target_property(_export_name ${_t} EXPORT_NAME)
  if(NOT _export_name)
    set(_export_name ${_t})
  endif()
  list(APPEND _plmap_components ${_export_name})
endforeach()
list(REMOVE_DUPLICATES _plmap_find_dependencies)
list(REMOVE_DUPLICATES _plmap_pc_requires)
list(REMOVE_DUPLICATES _plmap_pc_requires_private)
if(_plmap_pc_requires AND _plmap_pc_requires_private)
  list(REMOVE_ITEM _plmap_pc_requires_private ${_plmap_pc_requires})
endif()
list(REMOVE_DUPLICATES _plmap_pc_libs_extra)
list(REMOVE_DUPLICATES _plmap_pc_libs_private)

# The libraries in link order (each before the ones it uses), for plmap.pc.
set(_plmap_dependency_order "")
set(_remaining ${_plmap_libraries})
while(_remaining)
  set(_progress FALSE)
  foreach(_t IN LISTS _remaining)
    set(_ready TRUE)
    foreach(_dep IN LISTS _plmap_internal_deps_${_t})
      if(NOT _dep IN_LIST _plmap_dependency_order AND NOT _dep STREQUAL _t)
        set(_ready FALSE)
      endif()
    endforeach()
    if(_ready)
      list(APPEND _plmap_dependency_order ${_t})
      list(REMOVE_ITEM _remaining ${_t})
      set(_progress TRUE)
    endif()
  endforeach()
  if(NOT _progress)
    message(FATAL_ERROR "plmap install: cyclic links between ${_remaining}")
  endif()
endwhile()
set(_plmap_link_order ${_plmap_dependency_order})
list(REVERSE _plmap_link_order)

# ---- install rules ------------------------------------------------------------------------------
foreach(_include_dir IN LISTS _plmap_header_dirs)
  install(DIRECTORY "${_include_dir}/" DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}"
          COMPONENT plmap_development
          FILES_MATCHING PATTERN "*.hpp" PATTERN "*.ipp" PATTERN "*.h")
endforeach()

if(_plmap_libraries)
  install(TARGETS ${_plmap_libraries} EXPORT plmapTargets
          ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}" COMPONENT plmap_development
          LIBRARY DESTINATION "${CMAKE_INSTALL_LIBDIR}" COMPONENT plmap_runtime
          RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}" COMPONENT plmap_runtime
          INCLUDES DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}")
endif()

set(PLMAP_HAS_TOOL FALSE)
if(TARGET plmap_cli)
  # Exported as plmap::plmap, so downstream CMake can run the installed tool (e.g. in tests).
  set_target_properties(plmap_cli PROPERTIES EXPORT_NAME plmap)
  if(BUILD_SHARED_LIBS)
    set_target_properties(plmap_cli PROPERTIES INSTALL_RPATH "$ORIGIN/../${CMAKE_INSTALL_LIBDIR}")
  endif()
  install(TARGETS plmap_cli EXPORT plmapTargets
          RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}" COMPONENT plmap_runtime)
  set(PLMAP_HAS_TOOL TRUE)
endif()

if(NOT _plmap_libraries AND NOT TARGET plmap_cli)
  return()
endif()

install(EXPORT plmapTargets NAMESPACE plmap:: FILE plmapTargets.cmake
        DESTINATION "${PLMAP_INSTALL_CMAKEDIR}" COMPONENT plmap_development)

# plmapConfig.cmake: one find_dependency() per package the installed libraries link.
set(PLMAP_FIND_DEPENDENCIES "")
foreach(_dep IN LISTS _plmap_find_dependencies)
  if(_dep MATCHES "^PkgConfig-module (.+)$")
    string(APPEND PLMAP_FIND_DEPENDENCIES
           "find_dependency(PkgConfig)\n"
           "pkg_check_modules(${CMAKE_MATCH_1} REQUIRED QUIET IMPORTED_TARGET ${CMAKE_MATCH_1})\n")
  else()
    if(_dep STREQUAL "CGAL")
      string(APPEND PLMAP_FIND_DEPENDENCIES
             "set(CGAL_DO_NOT_WARN_ABOUT_CMAKE_BUILD_TYPE TRUE)\n")
    endif()
    string(APPEND PLMAP_FIND_DEPENDENCIES "find_dependency(${_dep})\n")
  endif()
endforeach()
set(PLMAP_COMPONENTS ${_plmap_components})
list(JOIN _plmap_components ", " PLMAP_COMPONENTS_TEXT)

configure_package_config_file(
  "${PROJECT_SOURCE_DIR}/cmake/plmapConfig.cmake.in"
  "${PROJECT_BINARY_DIR}/plmapConfig.cmake"
  INSTALL_DESTINATION "${PLMAP_INSTALL_CMAKEDIR}")
write_basic_package_version_file(
  "${PROJECT_BINARY_DIR}/plmapConfigVersion.cmake"
  VERSION ${PROJECT_VERSION}
  COMPATIBILITY SameMajorVersion)
install(FILES "${PROJECT_BINARY_DIR}/plmapConfig.cmake" "${PROJECT_BINARY_DIR}/plmapConfigVersion.cmake"
        DESTINATION "${PLMAP_INSTALL_CMAKEDIR}" COMPONENT plmap_development)

# plmap.pc: relocatable (the prefix is derived from where the file lies), so the same file works
# for `cmake --install --prefix P` with any P.
if(IS_ABSOLUTE "${PLMAP_INSTALL_PKGCONFIGDIR}")
  set(PLMAP_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
else()
  set(PLMAP_PC_PREFIX "\${pcfiledir}")
  string(REPLACE "/" ";" _pc_dir_parts "${PLMAP_INSTALL_PKGCONFIGDIR}")
  foreach(_part IN LISTS _pc_dir_parts)
    if(_part)
      string(APPEND PLMAP_PC_PREFIX "/..")
    endif()
  endforeach()
endif()
foreach(_kind LIBDIR INCLUDEDIR)
  if(IS_ABSOLUTE "${CMAKE_INSTALL_${_kind}}")
    set(PLMAP_PC_${_kind} "${CMAKE_INSTALL_${_kind}}")
  else()
    set(PLMAP_PC_${_kind} "\${prefix}/${CMAKE_INSTALL_${_kind}}")
  endif()
endforeach()
set(PLMAP_PC_LIBS "")
foreach(_t IN LISTS _plmap_link_order)
  get_target_property(_type ${_t} TYPE)
  if(_type STREQUAL "INTERFACE_LIBRARY")
    continue()
  endif()
  get_target_property(_output_name ${_t} OUTPUT_NAME)
  if(NOT _output_name)
    set(_output_name ${_t})
  endif()
  string(APPEND PLMAP_PC_LIBS " -l${_output_name}")
endforeach()
foreach(_flag IN LISTS _plmap_pc_libs_extra)
  string(APPEND PLMAP_PC_LIBS " ${_flag}")
endforeach()
string(STRIP "${PLMAP_PC_LIBS}" PLMAP_PC_LIBS)
list(JOIN _plmap_pc_requires " " PLMAP_PC_REQUIRES)
list(JOIN _plmap_pc_requires_private " " PLMAP_PC_REQUIRES_PRIVATE)
list(JOIN _plmap_pc_libs_private " " PLMAP_PC_LIBS_PRIVATE)
configure_file("${PROJECT_SOURCE_DIR}/cmake/plmap.pc.in" "${PROJECT_BINARY_DIR}/plmap.pc" @ONLY)
install(FILES "${PROJECT_BINARY_DIR}/plmap.pc" DESTINATION "${PLMAP_INSTALL_PKGCONFIGDIR}"
        COMPONENT plmap_development)

list(JOIN _plmap_libraries ", " _plmap_libraries_text)
message(STATUS "plmap install: libraries ${_plmap_libraries_text}; tool: ${PLMAP_HAS_TOOL}; "
               "packages re-found by plmapConfig.cmake: ${_plmap_find_dependencies}")
