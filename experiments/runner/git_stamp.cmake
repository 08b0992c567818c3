# Writes the commit the build is made from into OUTPUT (a header), at build time: run by the
# plmap_git_stamp target on every build, so results record the commit that was compiled, not the
# one checked out when CMake last configured. configure_file leaves OUTPUT untouched when nothing
# changed, so provenance.cpp is recompiled only when the commit (or the dirty state) moves.
#   cmake -DSOURCE_DIR=<repo> -DOUTPUT=<header> -DTEMPLATE=<git_info.hpp.in> -P git_stamp.cmake
set(PLMAP_GIT_DESCRIBE "unknown")
set(PLMAP_GIT_COMMIT "unknown")
find_package(Git QUIET)
if(GIT_FOUND AND EXISTS "${SOURCE_DIR}/.git")
  execute_process(COMMAND "${GIT_EXECUTABLE}" describe --always --dirty --tags
                  WORKING_DIRECTORY "${SOURCE_DIR}" OUTPUT_VARIABLE describe
                  OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE rc_describe)
  execute_process(COMMAND "${GIT_EXECUTABLE}" rev-parse HEAD
                  WORKING_DIRECTORY "${SOURCE_DIR}" OUTPUT_VARIABLE commit
                  OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE rc_commit)
  if(rc_describe EQUAL 0)
    set(PLMAP_GIT_DESCRIBE "${describe}")
  endif()
  if(rc_commit EQUAL 0)
    set(PLMAP_GIT_COMMIT "${commit}")
  endif()
endif()
configure_file("${TEMPLATE}" "${OUTPUT}" @ONLY)
