# Whether the Dune merger (bindings/dune) is built: PLMAP_BUILD_DUNE = ON (Dune required), OFF, or
# AUTO (built when found). Dune 2.9 as Debian packages it (libdune-grid-glue-dev and what it
# depends on) installs pkg-config files; its CMake modules want a Dune project of their own, so
# pkg-config it is. Sets PLMAP_DUNE_FOUND, the imported target PkgConfig::PLMAP_DUNE,
# PLMAP_DUNE_INCLUDE_DIRS and PLMAP_DUNE_VERSION_DEFINITIONS (the version macros of Dune's config.h).
set(PLMAP_DUNE_FOUND OFF)
string(TOUPPER "${PLMAP_BUILD_DUNE}" _plmap_dune_mode)
if(_plmap_dune_mode STREQUAL "OFF" OR _plmap_dune_mode STREQUAL "FALSE" OR _plmap_dune_mode STREQUAL "0")
  message(STATUS "Dune merger: off (PLMAP_BUILD_DUNE=${PLMAP_BUILD_DUNE})")
  return()
endif()
find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
  pkg_check_modules(PLMAP_DUNE QUIET IMPORTED_TARGET
                    dune-grid-glue>=2.9 dune-grid dune-geometry dune-common)
endif()
if(PLMAP_DUNE_FOUND)
  set(PLMAP_DUNE_FOUND ON)
  # Dune's headers test module versions with DUNE_VERSION_NEWER(DUNE_GRID, 2, 6), from macros a
  # Dune project's generated config.h defines; without them the 2.9 headers take their pre-2.6
  # branches and do not compile. Define them from the pkg-config versions.
  set(PLMAP_DUNE_VERSION_DEFINITIONS)
  foreach(module dune-common dune-geometry dune-grid dune-grid-glue)
    string(TOUPPER "${module}" macro)
    string(REPLACE "-" "_" macro "${macro}")
    string(REPLACE "." ";" parts "${PLMAP_DUNE_${module}_VERSION}.0.0")
    list(GET parts 0 major)
    list(GET parts 1 minor)
    list(GET parts 2 revision)
    list(APPEND PLMAP_DUNE_VERSION_DEFINITIONS ${macro}_VERSION_MAJOR=${major}
         ${macro}_VERSION_MINOR=${minor} ${macro}_VERSION_REVISION=${revision})
  endforeach()
  message(STATUS "Dune merger: with dune-grid-glue ${PLMAP_DUNE_dune-grid-glue_VERSION}")
elseif(_plmap_dune_mode STREQUAL "AUTO")
  message(STATUS "Dune merger: skipped, dune-grid-glue >= 2.9 not found by pkg-config "
                 "(Debian: libdune-grid-glue-dev)")
else()
  message(FATAL_ERROR "PLMAP_BUILD_DUNE=${PLMAP_BUILD_DUNE} but dune-grid-glue >= 2.9 was not found by "
                      "pkg-config (Debian: libdune-grid-glue-dev; or configure with -DPLMAP_BUILD_DUNE=AUTO)")
endif()
