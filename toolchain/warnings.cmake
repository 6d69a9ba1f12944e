# Warnings applied to every Petra target through petra_warnings.
add_library(petra_warnings INTERFACE)
target_compile_options(petra_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion
  -Wnon-virtual-dtor -Wold-style-cast -Wcast-align -Woverloaded-virtual
  -Wnull-dereference -Wdouble-promotion -Wformat=2 -Wimplicit-fallthrough)
if(PETRA_WERROR)
  target_compile_options(petra_warnings INTERFACE -Werror)
endif()
