# Partial renders, merge, checkpoints and resume from the command line (docs/farm.md); the doctest side is
# tests/render/merge_partials_test.cpp.
add_executable(rimu-exr-compare ${CMAKE_CURRENT_SOURCE_DIR}/cli/exr_compare_main.cpp)
target_link_libraries(rimu-exr-compare PRIVATE rimu_render)
set(farm_dir ${CMAKE_BINARY_DIR}/cli_farm)
file(MAKE_DIRECTORY ${farm_dir})
add_test(NAME "cli: rimu checkpoint, kill -9, SIGTERM and resume" COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/resume.sh
         $<TARGET_FILE:rimu> $<TARGET_FILE:rimu-exr-compare> ${farm_dir}/resume)
set(farm_tiny --resolution 16x12 --spp 8 -q)
rimu_cli_test("rimu --samples beyond --spp" 1 "--samples: --samples 0:16 reaches beyond the render's 8 samples"
              $<TARGET_FILE:rimu> ${farm_tiny} --samples 0:16 -o ${farm_dir}/never.exr)
rimu_cli_test("rimu --samples malformed" 1 "--samples: expected sample indices BEGIN:END"
              $<TARGET_FILE:rimu> ${farm_tiny} --samples 4-8 -o ${farm_dir}/never.exr)
rimu_cli_test("rimu --checkpoint malformed" 1 "--checkpoint: expected a positive duration"
              $<TARGET_FILE:rimu> ${farm_tiny} --checkpoint 10x -o ${farm_dir}/never.exr)
rimu_cli_test("rimu --resume of a plain render" 1 "plain.exr: not a partial render"
              sh -c "'$<TARGET_FILE:rimu>' --resolution 16x12 --spp 8 -q -o '${farm_dir}/plain.exr' && '$<TARGET_FILE:rimu>' --resume '${farm_dir}/plain.exr'")
rimu_cli_test("rimu --expect-scene-hash mismatch" 1 "hashes to [0-9a-f]{16}, not the expected 0000000000000000"
              $<TARGET_FILE:rimu> ${farm_tiny} --expect-scene-hash 0000000000000000 -o ${farm_dir}/never.exr)
rimu_cli_test("rimu merge without partials" 1 "partials is required|required"
              $<TARGET_FILE:rimu> merge -o ${farm_dir}/never.exr)
rimu_cli_test("rimu merge of a missing file" 1 "no-such-part.exr: cannot open the file: it does not exist"
              $<TARGET_FILE:rimu> merge ${farm_dir}/no-such-part.exr -o ${farm_dir}/never.exr)
add_test(NAME "cli: rimu-farm scripts run by hand: frames, merge, changed scene"
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/farm_scripts.sh $<TARGET_FILE:rimu> ${CMAKE_BINARY_DIR}/bin/rimu-farm
                 $<TARGET_FILE:rimu-exr-compare> ${CMAKE_CURRENT_SOURCE_DIR}/cli/frame_card.json ${farm_dir}/scripts)
rimu_cli_test("rimu frame placeholder without --frame" 1 "frame_card.json: uses \\$\\{frame\\} but no frame number was given"
              $<TARGET_FILE:rimu> ${CMAKE_CURRENT_SOURCE_DIR}/cli/frame_card.json -q -o ${farm_dir}/never.exr)
# A real Slurm on this machine (scripts/slurm-local.sh); skipped loudly (exit 77) when its daemons cannot start.
add_test(NAME "cli: rimu-farm on a single-node Slurm: 4-task array and merge equal a single render"
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/slurm_farm.sh ${PROJECT_SOURCE_DIR} $<TARGET_FILE:rimu>
                 ${CMAKE_BINARY_DIR}/bin/rimu-farm $<TARGET_FILE:rimu-exr-compare> ${farm_dir}/slurm)
set_tests_properties("cli: rimu-farm on a single-node Slurm: 4-task array and merge equal a single render"
                     PROPERTIES SKIP_RETURN_CODE 77 RUN_SERIAL TRUE TIMEOUT 600)
add_test(NAME "cli: scene hash covers referenced files: a CSV edited between partials is refused"
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/scene_files_hash.sh $<TARGET_FILE:rimu>
                 ${PROJECT_SOURCE_DIR}/data/scenes/cornell_box ${farm_dir}/scene_files)
# A camera path keyed by frame (docs/scene-format.md, "Camera paths"): needs --frame, renders with it.
rimu_cli_test("rimu camera keyframes without --frame" 1
              "camera_path.json.*/camera/keyframes.*needs a frame number: render with --frame N"
              $<TARGET_FILE:rimu> ${CMAKE_CURRENT_SOURCE_DIR}/cli/camera_path.json -q -o ${farm_dir}/never.exr)
add_test(NAME "cli: camera keyframes: frame 6 is the dolly's half-way camera, frames differ"
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/camera_path.sh $<TARGET_FILE:rimu> $<TARGET_FILE:rimu-exr-compare>
                 ${CMAKE_CURRENT_SOURCE_DIR}/cli/camera_path.json ${farm_dir}/camera_path)
# Values that reach the job scripts (scene and folder names, --out, --partition, --time, ...) with control
# characters are refused (no #SBATCH line can be cut and turned into a command); --spp and --frames are bounded.
add_test(NAME "cli: rimu-farm refuses control characters in script values, bounds --spp and --frames"
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/farm_hostile.sh ${CMAKE_BINARY_DIR}/bin/rimu-farm
                 ${CMAKE_CURRENT_SOURCE_DIR}/cli/frame_card.json ${farm_dir}/hostile)
# --resume continues the recorded job: a scene or --spp given with it is refused, not silently ignored.
rimu_cli_test("rimu --resume with a scene and --spp" 1
              "--resume: continues the job recorded in .*resumable.exr.*also given: the scene '.*frame_card.json', --spp"
              sh -c "'$<TARGET_FILE:rimu>' --resolution 16x12 --spp 8 -q --samples 0:4 -o '${farm_dir}/resumable.exr' && '$<TARGET_FILE:rimu>' '${CMAKE_CURRENT_SOURCE_DIR}/cli/frame_card.json' --resume '${farm_dir}/resumable.exr' --spp 16")
# SIGTERM before the first sample (while the scene loads) stops the render as documented: exit 0, output written.
add_test(NAME "cli: rimu SIGTERM while the scene loads: exit 0, output written, resumable"
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/early_signal.sh $<TARGET_FILE:rimu> ${farm_dir}/early_signal)
set_tests_properties("cli: rimu SIGTERM while the scene loads: exit 0, output written, resumable" PROPERTIES TIMEOUT 300)
