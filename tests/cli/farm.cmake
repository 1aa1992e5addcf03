# Partial renders, merge, checkpoints and resume from the command line (docs/farm.md); the doctest side is
# tests/render/merge_partials_test.cpp.
add_executable(rimu-exr-compare ${CMAKE_CURRENT_SOURCE_DIR}/cli/exr_compare_main.cpp)
target_link_libraries(rimu-exr-compare PRIVATE rimu_render)
set(farm_dir ${CMAKE_BINARY_DIR}/cli_farm)
file(MAKE_DIRECTORY ${farm_dir})
add_test(NAME "cli: rimu checkpoint, kill -9, SIGTERM and resume" COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/resume.sh
         $<TARGET_FILE:rimu> $<TARGET_FILE:rimu-exr-compare> ${farm_dir}/resume)
set(farm_tiny --resolution 16x12 --spp 8 -q)
rimu_cli_test("rimu --samples beyond --spp" 1 "--samples: --samples 0:16 reaches beyond the render's 8 samples"
              $<TARGET_FILE:rimu> ${farm_tiny} --samples 0:16 -o ${farm_dir}/never.exr)
rimu_cli_test("rimu --samples malformed" 1 "--samples: expected sample indices BEGIN:END"
              $<TARGET_FILE:rimu> ${farm_tiny} --samples 4-8 -o ${farm_dir}/never.exr)
rimu_cli_test("rimu --checkpoint malformed" 1 "--checkpoint: expected a positive duration"
              $<TARGET_FILE:rimu> ${farm_tiny} --checkpoint 10x -o ${farm_dir}/never.exr)
rimu_cli_test("rimu --resume of a plain render" 1 "plain.exr: not a partial render"
              sh -c "'$<TARGET_FILE:rimu>' --resolution 16x12 --spp 8 -q -o '${farm_dir}/plain.exr' && '$<TARGET_FILE:rimu>' --resume '${farm_dir}/plain.exr'")
rimu_cli_test("rimu --expect-scene-hash mismatch" 1 "hashes to [0-9a-f]{16}, not the expected 0000000000000000"
              $<TARGET_FILE:rimu> ${farm_tiny} --expect-scene-hash 0000000000000000 -o ${farm_dir}/never.exr)
rimu_cli_test("rimu merge without partials" 1 "partials is required|required"
              $<TARGET_FILE:rimu> merge -o ${farm_dir}/never.exr)
rimu_cli_test("rimu merge of a missing file" 1 "cannot read as OpenEXR"
              $<TARGET_FILE:rimu> merge ${farm_dir}/no-such-part.exr -o ${farm_dir}/never.exr)
