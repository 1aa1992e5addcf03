# The pbrt-v4 imagemap mappings that the sweep of pbrt-v4-scenes found listed (docs/pbrt-import.md, "Scenes of
# pbrt-v4-scenes"): the side-by-side scene renders under --strict, so nothing in it is listed any more.
rimu_cli_test("rimu --strict renders pbrt imagemap mappings with nothing listed" 0 "wrote"
              $<TARGET_FILE:rimu> ${CMAKE_CURRENT_SOURCE_DIR}/../bench/pbrt_scenes/imagemap_mappings.pbrt --strict
              --resolution 16x12 --spp 1 -o ${CMAKE_CURRENT_BINARY_DIR}/cli_scenes7_mappings.exr)
