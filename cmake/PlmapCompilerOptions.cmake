# Warning and sanitizer flags shared by every plmap target, applied through an interface target so
# that installed consumers do not inherit them.
add_library(plmap_compile_options INTERFACE)
target_compile_options(plmap_compile_options INTERFACE -Wall -Wextra -Wpedantic)
if(PLMAP_WERROR)
  target_compile_options(plmap_compile_options INTERFACE -Werror)
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    # GCC 12's flow-sensitive warnings fire inside libstdc++ itself (std::regex's std::function
    # under -O1 with sanitizers, string concatenation at -O3): keep them visible, not fatal.
    target_compile_options(plmap_compile_options INTERFACE
      -Wno-error=maybe-uninitialized -Wno-error=restrict)
  endif()
endif()
if(PLMAP_SANITIZE)
  target_compile_options(plmap_compile_options INTERFACE
    -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  target_link_options(plmap_compile_options INTERFACE -fsanitize=address,undefined)
endif()

# plmap_add_library(<folder> [PUBLIC deps...] [PRIVATE deps...])
# One library per top-level folder: sources from <folder>/src, public headers from
# <folder>/include/plmap/<folder>, target plmap_<folder> with alias plmap::<folder>.
function(plmap_add_library folder)
  cmake_parse_arguments(ARG "" "" "PUBLIC;PRIVATE" ${ARGN})
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/*.cpp)
  set(target plmap_${folder})
  add_library(${target} ${sources})
  add_library(plmap::${folder} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${folder} OUTPUT_NAME ${target})
  if(PLMAP_PYTHON_MODULE)
    # The Python extension is a shared module that links these static libraries: -fPIC. (Code
    # built as position-independent executable, GCC's default on Debian, accesses libc's data
    # such as stderr in a way a shared object cannot.)
    set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  endif()
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:include>)
  target_link_libraries(${target} PUBLIC ${ARG_PUBLIC}
    PRIVATE ${ARG_PRIVATE} $<BUILD_INTERFACE:plmap_compile_options>)
endfunction()
