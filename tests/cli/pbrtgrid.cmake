# pbrt-v4 grid media (docs/pbrt-import.md, "Media"): bad density grids exit 1 with the pbrt file:line and write nothing.
rimu_cli_test("rimu pbrt grid medium voxel count" 1 "bad_grid_count.pbrt:6: MakeNamedMedium \"cloud\" \\(uniformgrid\\): \"density\" has 7 values; expected nx·ny·nz = 2·2·2 = 8"
              $<TARGET_FILE:rimu> ${CMAKE_CURRENT_SOURCE_DIR}/data/pbrt/bad_grid_count.pbrt -o ${CMAKE_CURRENT_BINARY_DIR}/cli_never_written.exr -q)
rimu_cli_test("rimu pbrt grid medium negative density" 1 "bad_grid_negative.pbrt:6: MakeNamedMedium \"cloud\" \\(uniformgrid\\): \"density\" value 3 is -4.0; densities must be finite and >= 0"
              $<TARGET_FILE:rimu> ${CMAKE_CURRENT_SOURCE_DIR}/data/pbrt/bad_grid_negative.pbrt -o ${CMAKE_CURRENT_BINARY_DIR}/cli_never_written.exr -q)
rimu_cli_test("rimu pbrt grid medium NaN density" 1 "bad_grid_nan.pbrt:6: .*expected a finite number, found 'nan'"
              $<TARGET_FILE:rimu> ${CMAKE_CURRENT_SOURCE_DIR}/data/pbrt/bad_grid_nan.pbrt -o ${CMAKE_CURRENT_BINARY_DIR}/cli_never_written.exr -q)
add_test(NAME "cli: rimu pbrt bad grid medium writes no image"
         COMMAND bash -c "rm -f \"$1\"; \"$0\" \"$2\" -o \"$1\" -q; code=$?; [ $code = 1 ] && [ ! -e \"$1\" ]"
                 $<TARGET_FILE:rimu> ${CMAKE_CURRENT_BINARY_DIR}/pbrtgrid_never_written.exr
                 ${CMAKE_CURRENT_SOURCE_DIR}/data/pbrt/bad_grid_negative.pbrt)
# rimu-convert writes the grid inline: the JSON renders from another folder with no voxel file beside it.
add_test(NAME "cli: rimu-convert grid medium JSON renders on its own"
         COMMAND bash -c "set -e; rm -rf \"$2\"; mkdir -p \"$2\"; \"$1\" \"$3\" -o \"$2/grid.json\"; grep -q '\"interpolation\": \"trilinear\"' \"$2/grid.json\"; [ -z \"$(ls \"$2\" | grep -v grid.json)\" ]; \"$0\" \"$2/grid.json\" -o \"$2/grid.exr\" --spp 2 -q; [ -e \"$2/grid.exr\" ]"
                 $<TARGET_FILE:rimu> $<TARGET_FILE:rimu-convert> ${CMAKE_CURRENT_BINARY_DIR}/pbrtgrid_convert
                 ${CMAKE_CURRENT_SOURCE_DIR}/data/pbrt/grid_medium.pbrt)
