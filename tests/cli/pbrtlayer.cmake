# Coated materials from pbrt files (docs/pbrt-import.md): the five coated-ball scenes of the side-by-side render
# through the whole path integrator (closed form and random walks, next-event estimation with the walk's pdf)
# without a NaN, Inf or negative sample, in spectral and RGB transport.
foreach(coat smooth rough milky conductor paint_distant)
  rimu_cli_test("rimu pbrt coated ${coat}" 0 "discarded samples: 0 NaN, 0 Inf, 0 negative"
                $<TARGET_FILE:rimu> ${CMAKE_CURRENT_SOURCE_DIR}/../bench/pbrt_scenes/coated_${coat}.pbrt
                -o ${CMAKE_CURRENT_BINARY_DIR}/cli_pbrt_coated_${coat}.exr --spp 4)
endforeach()
rimu_cli_test("rimu pbrt coated conductor rgb transport" 0 "discarded samples: 0 NaN, 0 Inf, 0 negative"
              $<TARGET_FILE:rimu> ${CMAKE_CURRENT_SOURCE_DIR}/../bench/pbrt_scenes/coated_conductor.pbrt --wavelengths rgb
              -o ${CMAKE_CURRENT_BINARY_DIR}/cli_pbrt_coated_rgb.exr --spp 4)
