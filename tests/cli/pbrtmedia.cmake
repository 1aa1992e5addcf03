# pbrt-v4 media (docs/pbrt-import.md, "Media"): bad media input exits 1 with the pbrt file:line and writes nothing.
rimu_cli_test("rimu pbrt negative medium coefficient" 1 "bad_medium.pbrt:4: MakeNamedMedium \"rgb sigma_s\": RGB values must be >= 0"
              $<TARGET_FILE:rimu> ${CMAKE_CURRENT_SOURCE_DIR}/data/pbrt/bad_medium.pbrt -o ${CMAKE_CURRENT_BINARY_DIR}/cli_never_written.exr -q)
rimu_cli_test("rimu pbrt undefined medium" 1 "bad_medium_name.pbrt:7: Shape \"sphere\": the MediumInterface at .*bad_medium_name.pbrt:5 names the medium \"fgo\""
              $<TARGET_FILE:rimu> ${CMAKE_CURRENT_SOURCE_DIR}/data/pbrt/bad_medium_name.pbrt -o ${CMAKE_CURRENT_BINARY_DIR}/cli_never_written.exr -q)
