# libsodium (Debian libsodium-dev) as the imported target petra::sodium.
# Cross builds link Debian's multiarch static library (libsodium-dev:arm64), so
# the test binaries run under qemu without a target-side shared library path.
find_path(PETRA_SODIUM_INCLUDE_DIR sodium.h REQUIRED)
if(CMAKE_CROSSCOMPILING)
  find_library(PETRA_SODIUM_LIBRARY NAMES libsodium.a
    PATHS /usr/lib/${CMAKE_SYSTEM_PROCESSOR}-linux-gnu NO_DEFAULT_PATH NO_CMAKE_FIND_ROOT_PATH REQUIRED)
else()
  find_library(PETRA_SODIUM_LIBRARY NAMES sodium REQUIRED)
endif()
add_library(petra::sodium UNKNOWN IMPORTED)
set_target_properties(petra::sodium PROPERTIES
  IMPORTED_LOCATION ${PETRA_SODIUM_LIBRARY}
  INTERFACE_INCLUDE_DIRECTORIES ${PETRA_SODIUM_INCLUDE_DIR})
