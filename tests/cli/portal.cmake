# Environment portals: the benchmark room with its window as the sky's portal renders as shipped, and a portal that is
# not a rectangle is refused with exit 1 naming its JSON key.
rimu_cli_test("rimu renders light_sampling/ceiling_grid_room_portal.json" 0 "discarded samples: 0 NaN, 0 Inf, 0 negative"
              $<TARGET_FILE:rimu> ${CMAKE_SOURCE_DIR}/data/scenes/light_sampling/ceiling_grid_room_portal.json
              --spp 1 --resolution 24x16 -o ${CMAKE_BINARY_DIR}/cli_light_sampling_room_portal.exr)
rimu_cli_test("rimu refuses a portal that is not a rectangle" 1 "bad_portal.json: /lights/0/portals/0.*rectangle"
              $<TARGET_FILE:rimu> ${CMAKE_CURRENT_SOURCE_DIR}/cli/bad_portal.json
              -o ${CMAKE_BINARY_DIR}/cli_never_written.exr -q)
