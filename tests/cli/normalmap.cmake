# Normal and bump maps (docs/scene-format.md "Normal and bump maps", docs/pbrt-import.md): pbrt-v4's normalmap and
# displacement import with nothing ignored (--strict) and render without NaNs, including a texel that points below
# the surface; a material with both is an error at its key.
rimu_cli_test("rimu pbrt normal and bump maps" 0 "discarded samples: 0 NaN, 0 Inf, 0 negative"
              $<TARGET_FILE:rimu> ${CMAKE_CURRENT_SOURCE_DIR}/data/pbrt/normal_bump.pbrt --strict
              -o ${CMAKE_CURRENT_BINARY_DIR}/cli_pbrt_normal_bump.exr --spp 4)
rimu_cli_test("rimu normal map with displacement" 1 "/materials/both/displacement.*not both"
              $<TARGET_FILE:rimu> ${CMAKE_CURRENT_SOURCE_DIR}/cli/bad_normal_and_bump.json -o ${CMAKE_CURRENT_BINARY_DIR}/cli_never_written.exr -q)
