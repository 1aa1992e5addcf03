# Image textures are converted to spectra per texel at load (docs/upsampling.md "Fast path"): a texel that is NaN
# or infinite is a load-time error naming the file, the JSON key and the first bad texel (reading order, row 0 at
# the top), exit code 1. nonfinite_texels.pfm: 2×2, NaN at (1, 0) and +Inf at (0, 1).
rimu_cli_test("rimu non-finite texel" 1
              "nonfinite_texels.pfm.*/materials/poster/reflectance.*pixel \\(1, 0\\) is not a finite number"
              $<TARGET_FILE:rimu> ${CMAKE_CURRENT_SOURCE_DIR}/cli/bad_nonfinite_texture.json -o ${CMAKE_BINARY_DIR}/cli_never_written.exr -q)
