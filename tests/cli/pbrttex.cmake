# pbrt-v4 textures, textured roughness and the stochastic mix material (docs/pbrt-import.md, docs/scene-format.md
# "Textures", "mix"): a textured scene imports with nothing ignored (--strict) and renders without NaNs; a mix
# material that names itself is an error at its key.
rimu_cli_test("rimu pbrt textures" 0 "discarded samples: 0 NaN, 0 Inf, 0 negative"
              $<TARGET_FILE:rimu> ${CMAKE_CURRENT_SOURCE_DIR}/data/pbrt/textures.pbrt --strict
              -o ${CMAKE_CURRENT_BINARY_DIR}/cli_pbrt_textures.exr --spp 4)
rimu_cli_test("rimu mix material loop" 1 "/materials/b/materials/0.*mix materials refer to each other in a loop"
              $<TARGET_FILE:rimu> ${CMAKE_CURRENT_SOURCE_DIR}/cli/bad_mix_loop.json -o ${CMAKE_CURRENT_BINARY_DIR}/cli_never_written.exr -q)
