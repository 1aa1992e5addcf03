# The rimu tool's outputs, options and images (src/render/render_job.h, output_file.h, display_output.h,
# exr_output.h): refused before rendering with exit 1 when they cannot work, formats chosen by the file name, no
# NaN or Inf from the physical camera, a metered display image for photometric scenes, camera films displayed
# through their fitted matrix. tests/render/render_job_outputs_test.cpp checks the same through run_render_job.
set(out_scene ${CMAKE_CURRENT_SOURCE_DIR}/cli/photometric_card.json)
set(out_dir ${CMAKE_BINARY_DIR}/cli_output)
file(MAKE_DIRECTORY ${out_dir})
set(out_tiny --spp 1 --resolution 8x8 -q)
set(out_tiny_notes --spp 1 --resolution 8x8)  # without -q: for tests that read the notes and the summary
rimu_cli_test("rimu -o and --png name the same file" 1 "--png: -o and --png name the same file"
              $<TARGET_FILE:rimu> ${out_scene} -o ${out_dir}/same.exr --png ${out_dir}/./same.exr ${out_tiny})
rimu_cli_test("rimu -o needs .exr" 1 "-o: the scene-referred OpenEXR image needs a name ending in .exr"
              $<TARGET_FILE:rimu> ${out_scene} -o ${out_dir}/out.png ${out_tiny})
rimu_cli_test("rimu --png of an unknown format" 1 "--png: a display image is written as 8-bit sRGB PNG, JPEG or TIFF"
              $<TARGET_FILE:rimu> ${out_scene} -o ${out_dir}/a.exr --png ${out_dir}/v.bmp ${out_tiny})
rimu_cli_test("rimu --png into an unwritable folder" 1 "/proc/rimu-x.png.*cannot create a file in the output folder"
              $<TARGET_FILE:rimu> ${out_scene} -o ${out_dir}/a.exr --png /proc/rimu-x.png ${out_tiny})
rimu_cli_test("rimu -o into an unwritable folder" 1 "/proc/rimu-x.exr.*cannot create a file in the output folder"
              $<TARGET_FILE:rimu> ${out_scene} -o /proc/rimu-x.exr ${out_tiny})
rimu_cli_test("rimu --exposure nan" 1 "--exposure: the display exposure must be a number of stops in -60 to 60, got nan"
              $<TARGET_FILE:rimu> ${out_scene} -o ${out_dir}/a.exr --png ${out_dir}/v.png --exposure nan ${out_tiny})
rimu_cli_test("rimu tiny ISO, shutter and f-number" 1 "--iso: expected an ISO speed in 0.001 to 10000000, got 1e-300"
              $<TARGET_FILE:rimu> ${out_scene} -o ${out_dir}/a.exr --iso 1e-300 --shutter 1e-300 --f-number 1e-300
              ${out_tiny})
rimu_cli_test("rimu --ev 2000" 1 "--ev: expected an exposure compensation in stops in -30 to 30, got 2000"
              $<TARGET_FILE:rimu> ${out_scene} -o ${out_dir}/a.exr --ev 2000 ${out_tiny})
rimu_cli_test("rimu --iso inf" 1 "--iso: expected an ISO speed in 0.001 to 10000000, got inf"
              $<TARGET_FILE:rimu> ${out_scene} -o ${out_dir}/a.exr --iso inf ${out_tiny})
rimu_cli_test("rimu photometric scene without exposure is metered" 0 "the display image is metered"
              $<TARGET_FILE:rimu> ${out_scene} -o ${out_dir}/metered.exr --png ${out_dir}/metered.png ${out_tiny_notes})
rimu_cli_test("rimu camera film displayed through its fitted matrix" 0 "camera-to-XYZ matrix fitted to the 24 ColorChecker"
              $<TARGET_FILE:rimu> ${out_scene} -o ${out_dir}/camera.exr --png ${out_dir}/camera.png
              --film camera:nikon_d850 ${out_tiny_notes})
rimu_cli_test("rimu nearly black display image is warned about" 0 "100 % of .*black.png is nearly black"
              $<TARGET_FILE:rimu> ${out_scene} -o ${out_dir}/black.exr --png ${out_dir}/black.png --exposure -30
              ${out_tiny})
add_test(NAME "cli: rimu output files from the shell"
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/output_files.sh $<TARGET_FILE:rimu> ${out_scene}
                 ${CMAKE_BINARY_DIR}/cli_output_shell)
# 32-bit float EXR is the default; --half is opt-in and --float (the old opt-in) is still accepted, but not with --half.
rimu_cli_test("rimu --half and --float together" 1 "--half excludes --float|--float excludes --half"
              $<TARGET_FILE:rimu> ${out_scene} -o ${out_dir}/a.exr --half --float ${out_tiny})
rimu_cli_test("rimu --float of old command lines is accepted" 0 "wrote .*float.exr"
              $<TARGET_FILE:rimu> ${out_scene} -o ${out_dir}/float.exr --float ${out_tiny_notes})
# An output that is one of the tool's inputs (same name, symbolic or hard link) is refused by every tool.
add_test(NAME "cli: outputs that are inputs are refused by every tool (names, symbolic and hard links)"
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/output_not_input.sh ${CMAKE_BINARY_DIR}/bin ${PROJECT_SOURCE_DIR}
                 ${CMAKE_BINARY_DIR}/cli_output/not_input)
# -q: nothing on stderr but warnings and errors.
add_test(NAME "cli: rimu -q prints nothing but warnings and errors"
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/quiet.sh $<TARGET_FILE:rimu>
                 ${CMAKE_CURRENT_SOURCE_DIR}/cli/photometric_card.json ${CMAKE_BINARY_DIR}/cli_output/quiet)
# A broken PNG texture: one message of Rimu's naming the file; libpng's own line does not reach stderr.
add_test(NAME "cli: a broken PNG texture is one message naming the file, without libpng's own line"
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/image_messages.sh $<TARGET_FILE:rimu>
                 ${CMAKE_BINARY_DIR}/cli_output/image_messages)
