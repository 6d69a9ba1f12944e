# cppcheck over the flight rooms: `cmake --build <dir> --target cppcheck`, and
# the ctest test static.cppcheck (tests/CMakeLists.txt) so the test command
# keeps it clean. A finding exits 1.
find_program(PETRA_CPPCHECK cppcheck)
set(PETRA_CPPCHECK_ARGS
    --enable=warning,performance,portability --std=c++20
    --inline-suppr --error-exitcode=1 --quiet
    --suppress=missingIncludeSystem --suppress=unmatchedSuppression
    # Image views, spans and Rects are small handles passed by value on purpose
    # (like std::span): a reference would add an indirection, not save a copy.
    --suppress=passedByValue
    -I ${CMAKE_SOURCE_DIR}
    ${CMAKE_SOURCE_DIR}/algo ${CMAKE_SOURCE_DIR}/fsw ${CMAKE_SOURCE_DIR}/hal
    ${CMAKE_SOURCE_DIR}/cmd ${CMAKE_SOURCE_DIR}/tlm)
if(PETRA_CPPCHECK)
  add_custom_target(cppcheck
    COMMAND ${PETRA_CPPCHECK} ${PETRA_CPPCHECK_ARGS}
    WORKING_DIRECTORY ${CMAKE_SOURCE_DIR}
    COMMENT "cppcheck on flight code")
endif()

# `cmake --build <dir> --target tidy` runs clang-tidy over the flight rooms.
find_program(PETRA_CLANG_TIDY NAMES clang-tidy clang-tidy-14)
if(PETRA_CLANG_TIDY)
  file(GLOB_RECURSE petra_tidy_sources CONFIGURE_DEPENDS
    ${CMAKE_SOURCE_DIR}/algo/*.cpp ${CMAKE_SOURCE_DIR}/fsw/*.cpp ${CMAKE_SOURCE_DIR}/hal/*.cpp
    ${CMAKE_SOURCE_DIR}/cmd/*.cpp ${CMAKE_SOURCE_DIR}/tlm/*.cpp)
  add_custom_target(tidy
    COMMAND ${PETRA_CLANG_TIDY} -p ${CMAKE_BINARY_DIR} --quiet ${petra_tidy_sources}
    WORKING_DIRECTORY ${CMAKE_SOURCE_DIR}
    COMMENT "clang-tidy on flight code")
endif()
