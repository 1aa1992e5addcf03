# bench/pbrt_side_by_side.sh's image comparison tool (built with the benchmarks).
if(RIMU_BUILD_BENCHMARKS)
  add_test(NAME "cli: rimu-pbrt-image-compare on two renders of the pbrt Cornell box"
           COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/pbrt_image_compare.sh $<TARGET_FILE:rimu>
                   $<TARGET_FILE:rimu-pbrt-image-compare> ${CMAKE_CURRENT_SOURCE_DIR}/data/pbrt
                   ${CMAKE_CURRENT_BINARY_DIR}/cli_pbrt_image_compare)
endif()
