# ASan + UBSan for the `asan` and `check` presets (PETRA_SANITIZE). Applied
# globally so tests and libraries agree. No recovery: the first report ends
# the program (ASan never recovers unless asked), so a test cannot pass over
# undefined behaviour.
if(PETRA_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()

# petra_sanitize_off_rover(): for the code that does not fly (tests/, sim/).
# UBSan's null and alignment checks there halve the compile time of the check
# build (gtest and Eigen inlined at -O2: 65 s -> 25 s for one test file); a null
# dereference still ends in ASan's SEGV report with its stack, and the flight
# rooms (algo, hal, cmd, tlm, fsw) keep every check.
macro(petra_sanitize_off_rover)
  if(PETRA_SANITIZE)
    add_compile_options(-fno-sanitize=null,alignment)
  endif()
endmacro()
