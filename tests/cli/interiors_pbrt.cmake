# The interior benchmark's rooms in pbrt-v4's format (data/scenes/interiors/write_pbrt_versions.py; docs/benchmarks.md,
# "Interiors against pbrt-v4"): the committed .pbrt files and the downlights' goniometric image are what the script
# writes from the JSON rooms (so the two stay one scene), and Rimu imports each of them with nothing ignored.
add_test(NAME "interiors: the pbrt versions are written from the JSON rooms"
         COMMAND ${RIMU_PYTHON3} ${PROJECT_SOURCE_DIR}/data/scenes/interiors/write_pbrt_versions.py --check)
foreach(room daylit_room_open daylit_room_glazed door_ajar night_room_downlights)
  rimu_cli_test("interiors: rimu imports ${room}.pbrt with nothing ignored" 0 "discarded samples: 0 NaN, 0 Inf, 0 negative"
                $<TARGET_FILE:rimu> ${PROJECT_SOURCE_DIR}/data/scenes/interiors/${room}.pbrt --strict --spp 1
                --resolution 32x18 -o ${CMAKE_BINARY_DIR}/cli_interiors_${room}.exr)
endforeach()
