# ASan + UBSan for the `asan` preset. Applied globally so tests and libraries agree.
if(PETRA_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()
