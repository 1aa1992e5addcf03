# Image textures are converted to spectra per texel at load (docs/upsampling.md "Fast path"): a texel that is NaN
# or infinite is a load-time error naming the file, the JSON key and the first bad texel (reading order, row 0 at
# the top), exit code 1. nonfinite_texels.pfm: 2×2, NaN at (1, 0) and +Inf at (0, 1).
rimu_cli_test("rimu non-finite texel" 1
              "nonfinite_texels.pfm.*/materials/poster/reflectance.*pixel \\(1, 0\\) is not a finite number"
              $<TARGET_FILE:rimu> ${CMAKE_CURRENT_SOURCE_DIR}/cli/bad_nonfinite_texture.json -o ${CMAKE_BINARY_DIR}/cli_never_written.exr -q)

# Image headers sized beyond their file and environment pixels whose radiance overflows: exit 1 naming the file
# (before: exit 2 "out of memory" after trying to allocate 51.5 GB or 120 GB; a FLT_MAX pixel silently dropped).
rimu_cli_test("rimu refuses a 69-byte PNG claiming 65535x65535 pixels" 1
              "bad_header_65535x65535.png.*65535 x 65535 pixels, more than the limit"
              $<TARGET_FILE:rimu> ${CMAKE_CURRENT_SOURCE_DIR}/cli/bad_image_header.json -o ${CMAKE_BINARY_DIR}/cli_never_written.exr -q)
rimu_cli_test("rimu refuses a 70-byte PFM claiming 100000x100000 pixels" 1
              "bad_header_100000x100000.pfm.*100000 x 100000 pixels, more than the limit"
              $<TARGET_FILE:rimu> ${CMAKE_CURRENT_SOURCE_DIR}/cli/bad_environment_header.json -o ${CMAKE_BINARY_DIR}/cli_never_written.exr -q)
rimu_cli_test("rimu refuses an environment pixel of FLT_MAX, naming it" 1
              "flt_max_pixel.pfm': pixel \\(1, 0\\) is \\(3.40282e\\+38, 0.5, 0.5\\).*at most 1e30"
              $<TARGET_FILE:rimu> ${CMAKE_CURRENT_SOURCE_DIR}/cli/bad_flt_max_environment.json -o ${CMAKE_BINARY_DIR}/cli_never_written.exr -q)
