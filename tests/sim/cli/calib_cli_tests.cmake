# `petra calib` and `petra click` on the real sample set (docs/icd.md,
# command lines): what outside tools rely on, the "RMS" lines included.
set(PETRA_CHESSBOARD_DATA ${PROJECT_SOURCE_DIR}/../shared/data/chessboard-opencv)
set(PETRA_CLI_OUT ${CMAKE_BINARY_DIR}/cli_tests)
file(MAKE_DIRECTORY ${PETRA_CLI_OUT})

add_test(NAME sim_cli.calib_sample_set
  COMMAND petra calib --cols 9 --rows 6 --square 1
          --left ${PETRA_CHESSBOARD_DATA}/left*.jpg --right ${PETRA_CHESSBOARD_DATA}/right*.jpg
          --out ${PETRA_CLI_OUT}/calib_sample.json)
set_tests_properties(sim_cli.calib_sample_set PROPERTIES
  LABELS integration FIXTURES_SETUP calib_sample
  PASS_REGULAR_EXPRESSION "left01.jpg +0\\.[0-9]+ +right01.jpg +0\\.[0-9]+.*stereo: RMS 0\\.[0-9]+ px overall.*baseline 3\\.3[0-9]+ mm.*wrote")

add_test(NAME sim_cli.info_reads_calib_output COMMAND petra info --calib ${PETRA_CLI_OUT}/calib_sample.json)
set_tests_properties(sim_cli.info_reads_calib_output PROPERTIES
  LABELS integration FIXTURES_REQUIRED calib_sample PASS_REGULAR_EXPRESSION "rig +baseline 3\\.3")

add_test(NAME sim_cli.click_sample_set
  COMMAND petra click --calib ${PETRA_CLI_OUT}/calib_sample.json --uv 300,200
          --left ${PETRA_CHESSBOARD_DATA}/left01.jpg --right ${PETRA_CHESSBOARD_DATA}/right01.jpg)
set_tests_properties(sim_cli.click_sample_set PROPERTIES
  LABELS integration FIXTURES_REQUIRED calib_sample
  PASS_REGULAR_EXPRESSION "epipolar line in the right image.*match in the right image: \\(1[0-9][0-9]\\.[0-9]+, 21[0-9]\\.[0-9]+\\).*3D point")

add_test(NAME sim_cli.calib_wrong_board_size
  COMMAND petra calib --cols 7 --rows 6 --square 1
          --left ${PETRA_CHESSBOARD_DATA}/left*.jpg --right ${PETRA_CHESSBOARD_DATA}/right*.jpg
          --out ${PETRA_CLI_OUT}/never.json)
set_tests_properties(sim_cli.calib_wrong_board_size PROPERTIES LABELS integration
  PASS_REGULAR_EXPRESSION "rejected .*left01.jpg: board not found: 9x6 inner corners visible, more than the 7x6 expected.*petra calib: the board was found in 0 left and 0 right images of 13 pairs, need at least 3 each")

add_test(NAME sim_cli.calib_no_images
  COMMAND petra calib --cols 9 --rows 6 --square 1 --left /nonexistent/left*.jpg
          --right /nonexistent/right*.jpg --out ${PETRA_CLI_OUT}/never.json)
set_tests_properties(sim_cli.calib_no_images PROPERTIES LABELS integration
  PASS_REGULAR_EXPRESSION "petra calib: no files match '/nonexistent/left\\*.jpg'")

add_test(NAME sim_cli.click_bad_uv COMMAND petra click --calib ${PETRA_CLI_OUT}/calib_sample.json --uv 300)
set_tests_properties(sim_cli.click_bad_uv PROPERTIES LABELS integration FIXTURES_REQUIRED calib_sample
  PASS_REGULAR_EXPRESSION "petra click: --uv: expected u,v")

# --max-depth bounds the search; one not beyond --min-depth is refused naming both.
add_test(NAME sim_cli.click_depth_range_empty
  COMMAND petra click --calib ${PETRA_CLI_OUT}/calib_sample.json --uv 300,200
          --min-depth 50 --max-depth 40)
set_tests_properties(sim_cli.click_depth_range_empty PROPERTIES LABELS integration
  FIXTURES_REQUIRED calib_sample
  PASS_REGULAR_EXPRESSION "petra click: --max-depth must exceed --min-depth")

add_test(NAME sim_cli.click_negative_depth
  COMMAND petra click --calib ${PETRA_CLI_OUT}/calib_sample.json --uv 300,200 --max-depth -1)
set_tests_properties(sim_cli.click_negative_depth PROPERTIES LABELS integration
  FIXTURES_REQUIRED calib_sample PASS_REGULAR_EXPRESSION "petra click: --max-depth: must be > 0 mm")

# A range that stops short of the true match (depth 15.9 square units): the
# point found lies inside it (3 baselines = 9.98 to 12).
add_test(NAME sim_cli.click_max_depth_bounds_the_search
  COMMAND petra click --calib ${PETRA_CLI_OUT}/calib_sample.json --uv 300,200 --max-depth 12
          --left ${PETRA_CHESSBOARD_DATA}/left01.jpg --right ${PETRA_CHESSBOARD_DATA}/right01.jpg)
set_tests_properties(sim_cli.click_max_depth_bounds_the_search PROPERTIES
  LABELS integration FIXTURES_REQUIRED calib_sample
  PASS_REGULAR_EXPRESSION "3D point .* depth (9\\.9[89]|1[01]\\.[0-9]+|12\\.000) mm, rays")
