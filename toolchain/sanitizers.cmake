# ASan + UBSan for the `asan` and `check` presets (PETRA_SANITIZE). Applied
# globally so tests and libraries agree. No recovery: the first report ends
# the program (ASan never recovers unless asked), so a test cannot pass over
# undefined behaviour.
if(PETRA_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()
