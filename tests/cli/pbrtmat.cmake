# pbrt-v4 appearance and camera import (docs/pbrt-import.md): an equal-area environment map, a cropped film and an
# orthographic camera render from the command line; a missing spectrum file exits 1 with its file:line.
rimu_cli_test("rimu pbrt environment map" 0 "discarded samples: 0 NaN, 0 Inf, 0 negative"
              $<TARGET_FILE:rimu> ${CMAKE_CURRENT_SOURCE_DIR}/data/pbrt/envmap_texel.pbrt -o ${CMAKE_CURRENT_BINARY_DIR}/cli_pbrt_envmap.exr --spp 4)
rimu_cli_test("rimu pbrt orthographic camera" 0 "discarded samples: 0 NaN, 0 Inf, 0 negative"
              $<TARGET_FILE:rimu> ${CMAKE_CURRENT_SOURCE_DIR}/data/pbrt/orthographic.pbrt -o ${CMAKE_CURRENT_BINARY_DIR}/cli_pbrt_ortho.exr --spp 4)
rimu_cli_test("rimu pbrt crop window" 0 "discarded samples: 0 NaN, 0 Inf, 0 negative"
              $<TARGET_FILE:rimu> ${CMAKE_CURRENT_SOURCE_DIR}/data/pbrt/crop.pbrt -o ${CMAKE_CURRENT_BINARY_DIR}/cli_pbrt_crop.exr --spp 4)
rimu_cli_test("rimu pbrt missing spectrum file" 1 "bad_spectrum_file.pbrt:6: cannot find the spectrum file"
              $<TARGET_FILE:rimu> ${CMAKE_CURRENT_SOURCE_DIR}/data/pbrt/bad_spectrum_file.pbrt -o ${CMAKE_CURRENT_BINARY_DIR}/cli_never_written.exr -q)
