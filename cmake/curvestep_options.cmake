# Compile options shared by every curvestep target: warnings, sanitizers, embedded flags.

add_library(curvestep_warnings INTERFACE)
add_library(curvestep::warnings ALIAS curvestep_warnings)
target_compile_options(curvestep_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wsign-conversion
  -Wnon-virtual-dtor -Wold-style-cast -Wcast-align -Wdouble-promotion
  $<$<BOOL:${CURVESTEP_WARNINGS_AS_ERRORS}>:-Werror>
  # GCC 12 reports a false -Wrestrict inside std::string concatenation when optimising (GCC bug
  # 105329); it fires in libstdc++'s own code, not ours.
  $<$<AND:$<CXX_COMPILER_ID:GNU>,$<VERSION_LESS:$<CXX_COMPILER_VERSION>,13>>:-Wno-restrict>)

# Bare-metal rules: no exceptions, no RTTI, no thread-safe statics (no __cxa_guard_*),
# and no contraction of a*b+c into FMA, so float results match across targets.
add_library(curvestep_embedded INTERFACE)
add_library(curvestep::embedded ALIAS curvestep_embedded)
target_compile_options(curvestep_embedded INTERFACE
  -fno-exceptions -fno-rtti -fno-threadsafe-statics -ffunction-sections -fdata-sections
  -ffp-contract=off)

if(CURVESTEP_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
  # GCC 12 reports false -Wmaybe-uninitialized under -fsanitize (e.g. inside std::regex).
  target_compile_options(curvestep_warnings INTERFACE -Wno-maybe-uninitialized)
endif()

# Same floating-point results on host and target: never fuse multiply-add implicitly.
add_compile_options(-ffp-contract=off)

# On a board, __FILE__ (in CURVESTEP_EXPECTS's messages) relative to the source tree, so an image's
# flash and its bytes do not depend on where the tree was checked out. (Host tests find docs/ from
# their own absolute __FILE__.)
if(CMAKE_CROSSCOMPILING)
  add_compile_options(-fmacro-prefix-map=${CMAKE_SOURCE_DIR}/=)
endif()
