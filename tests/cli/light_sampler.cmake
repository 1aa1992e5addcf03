# Light sampler choice: the option, the scene key, and the load-time warning about a starved light.
rimu_cli_test("rimu power light sampler renders" 0 "discarded samples: 0 NaN, 0 Inf, 0 negative"
              $<TARGET_FILE:rimu> --light-sampler power --spp 2 --resolution 16x16
              -o ${CMAKE_BINARY_DIR}/cli_power_sampler.exr)
rimu_cli_test("rimu bvh-spectral light sampler renders" 0 "discarded samples: 0 NaN, 0 Inf, 0 negative"
              $<TARGET_FILE:rimu> --light-sampler bvh-spectral --spp 2 --resolution 16x16
              -o ${CMAKE_BINARY_DIR}/cli_bvh_spectral_sampler.exr)
rimu_cli_test("rimu unknown light sampler" 1 "--light-sampler: .*bvh"
              $<TARGET_FILE:rimu> --light-sampler tree -o ${CMAKE_BINARY_DIR}/cli_never_written.exr)
rimu_cli_test("rimu unknown light sampler in a scene" 1 "bad_light_sampler.json: /integrator/light_sampler.*bvh"
              $<TARGET_FILE:rimu> ${CMAKE_CURRENT_SOURCE_DIR}/cli/bad_light_sampler.json
              -o ${CMAKE_BINARY_DIR}/cli_never_written.exr -q)
rimu_cli_test("rimu warns about a light the power sampler starves" 0
              "warning: 'key' \\(/lights/0\\) gets [0-9.e-]+ % of the light samples"
              $<TARGET_FILE:rimu> ${CMAKE_CURRENT_SOURCE_DIR}/cli/starved_spot.json
              -o ${CMAKE_BINARY_DIR}/cli_starved_spot.exr -q)
# The light-sampling benchmark's scenes render as shipped (the bench loads the same files), and the 100 m floor
# makes the power sampler warn that it starves the spot.
foreach(scene spot_3m_floor ceiling_grid_room street)
  rimu_cli_test("rimu renders light_sampling/${scene}.json" 0 "discarded samples: 0 NaN, 0 Inf, 0 negative"
                $<TARGET_FILE:rimu> ${CMAKE_SOURCE_DIR}/data/scenes/light_sampling/${scene}.json
                --spp 1 --resolution 24x16 -o ${CMAKE_BINARY_DIR}/cli_light_sampling_${scene}.exr)
endforeach()
# The coloured-light scenes, with wavelength-aware choice as the benchmark renders them.
foreach(scene red_blue_lamps rgb_led_panels sodium_mercury_square)
  rimu_cli_test("rimu renders light_sampling/${scene}.json with bvh-spectral" 0
                "discarded samples: 0 NaN, 0 Inf, 0 negative"
                $<TARGET_FILE:rimu> ${CMAKE_SOURCE_DIR}/data/scenes/light_sampling/${scene}.json
                --light-sampler bvh-spectral --spp 1 --resolution 24x16
                -o ${CMAKE_BINARY_DIR}/cli_light_sampling_${scene}.exr)
endforeach()
rimu_cli_test("rimu power sampler starves the spot over a 100 m floor" 0 "warning: 'spot' \\(/lights/0\\) gets"
              $<TARGET_FILE:rimu> ${CMAKE_SOURCE_DIR}/data/scenes/light_sampling/spot_100m_floor.json
              --light-sampler power --spp 1 --resolution 24x16 -q -o ${CMAKE_BINARY_DIR}/cli_light_sampling_100m.exr)
