# Warning and sanitizer flags shared by every plmap target, applied through an interface target so
# that installed consumers do not inherit them.
add_library(plmap_compile_options INTERFACE)
target_compile_options(plmap_compile_options INTERFACE -Wall -Wextra -Wpedantic)
if(PLMAP_WERROR)
  target_compile_options(plmap_compile_options INTERFACE -Werror)
endif()
if(PLMAP_SANITIZE)
  target_compile_options(plmap_compile_options INTERFACE
    -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  target_link_options(plmap_compile_options INTERFACE -fsanitize=address,undefined)
endif()
