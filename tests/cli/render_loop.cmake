# The lighter's loop from the command line (docs/rendering.md): the render log off a terminal, a time budget with
# SIGTERM and --resume, the preview; and the options' messages. The doctest side is
# tests/render/time_budget_test.cpp. Uses rimu-exr-compare (farm.cmake).
set(loop_dir ${CMAKE_BINARY_DIR}/cli_render_loop)
file(MAKE_DIRECTORY ${loop_dir})
add_test(NAME "cli: rimu render log, time budget with SIGTERM and resume, preview"
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/render_loop.sh $<TARGET_FILE:rimu> $<TARGET_FILE:rimu-exr-compare>
                 ${loop_dir}/run)
set(loop_tiny --resolution 16x12 -q)
rimu_cli_test("rimu --time malformed" 1 "--time: expected a positive duration such as 30s"
              $<TARGET_FILE:rimu> ${loop_tiny} --time 90x -o ${loop_dir}/never.exr)
rimu_cli_test("rimu --time with --samples" 1 "--samples: a render to a time budget \\(--time\\)"
              $<TARGET_FILE:rimu> ${loop_tiny} --time 1s --spp 8 --samples 0:4 -o ${loop_dir}/never.exr)
rimu_cli_test("rimu --preview-interval without --preview" 1 "--preview-interval: needs --preview"
              $<TARGET_FILE:rimu> ${loop_tiny} --preview-interval 2s -o ${loop_dir}/never.exr)
rimu_cli_test("rimu --preview the same file as --png" 1 "--preview: names the same file as --png"
              $<TARGET_FILE:rimu> ${loop_tiny} --png ${loop_dir}/same.png --preview ${loop_dir}/same.png
              -o ${loop_dir}/never.exr)
rimu_cli_test("rimu --preview of an unknown format" 1 "--preview"
              $<TARGET_FILE:rimu> ${loop_tiny} --preview ${loop_dir}/preview.exr -o ${loop_dir}/never.exr)
rimu_cli_test("rimu --noise-threshold with --samples" 1 "--samples: --noise-threshold .*cannot be split"
              $<TARGET_FILE:rimu> ${loop_tiny} --noise-threshold 0.01 --spp 8 --samples 0:4 -o ${loop_dir}/never.exr)
rimu_cli_test("rimu --noise-threshold out of range" 1 "--noise-threshold"
              $<TARGET_FILE:rimu> ${loop_tiny} --noise-threshold 0 -o ${loop_dir}/never.exr)
