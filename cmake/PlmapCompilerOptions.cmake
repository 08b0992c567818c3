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
if(PLMAP_BUILD_FUZZERS)
  # libFuzzer needs clang; the check links a tiny fuzz target, so a clang without the fuzzer
  # runtime (Debian: libclang-rt-dev) is reported here rather than at the first link.
  include(CheckCXXSourceCompiles)
  set(CMAKE_REQUIRED_FLAGS -fsanitize=fuzzer)
  set(CMAKE_REQUIRED_LINK_OPTIONS -fsanitize=fuzzer)
  check_cxx_source_compiles([[
    #include <cstddef>
    #include <cstdint>
    extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t*, std::size_t) { return 0; }
  ]] PLMAP_COMPILER_HAS_LIBFUZZER)
  unset(CMAKE_REQUIRED_FLAGS)
  unset(CMAKE_REQUIRED_LINK_OPTIONS)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang" OR NOT PLMAP_COMPILER_HAS_LIBFUZZER)
    message(FATAL_ERROR "PLMAP_BUILD_FUZZERS needs clang with libFuzzer (-fsanitize=fuzzer); on "
                        "Debian install clang and libclang-rt-dev and configure with "
                        "-DCMAKE_CXX_COMPILER=clang++ (scripts/fuzz does both)")
  endif()
  # Every library gets coverage instrumentation for the fuzzer and both sanitizers; only the
  # fuzz targets link libFuzzer's main (tests/fuzz/CMakeLists.txt).
  target_compile_options(plmap_compile_options INTERFACE
    -fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer
    -fno-sanitize-recover=undefined)
  target_link_options(plmap_compile_options INTERFACE -fsanitize=address,undefined)
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
