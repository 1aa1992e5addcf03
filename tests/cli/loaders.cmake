# Input readers and scene loading under hostile input (docs/scene-format.md, "Limits"): each case exits with 1 and a
# message naming the file and the line or key, where it used to abort, hang, allocate gigabytes or lose data.
set(loaders_dir ${CMAKE_CURRENT_SOURCE_DIR}/cli)
set(loaders_exr ${CMAKE_CURRENT_BINARY_DIR}/cli_loaders_never_written.exr)

rimu_cli_test("loaders: camera beyond Embree's range" 1 "bad_far_camera.json: /camera/from: the camera position .*1e\\+18"
              $<TARGET_FILE:rimu> ${loaders_dir}/bad_far_camera.json -o ${loaders_exr} -q)
rimu_cli_test("loaders: a directory as the scene" 1 "cli: is a directory"
              $<TARGET_FILE:rimu> ${loaders_dir} -o ${loaders_exr} -q)
rimu_cli_test("loaders: /dev/zero as the scene" 1 "/dev/zero: is a character device"
              $<TARGET_FILE:rimu> /dev/zero -o ${loaders_exr} -q)
rimu_cli_test("loaders: /dev/urandom as a spectrum" 1 "/dev/urandom: is a character device"
              $<TARGET_FILE:rimu-colour> report --csv /dev/urandom)
rimu_cli_test("loaders: rimu-light inspect /dev/zero" 1 "/dev/zero: is a character device"
              $<TARGET_FILE:rimu-light> inspect /dev/zero)
rimu_cli_test("loaders: NUL byte in a scene" 1 "bad_nul_byte.json:3: column 3: a NUL byte"
              $<TARGET_FILE:rimu> ${loaders_dir}/bad_nul_byte.json -o ${loaders_exr} -q)
rimu_cli_test("loaders: voxel grid shorter than its header says" 1
              "/media/fog/file: .*bad_short.rvol: the header announces 1024 × 1024 × 1024 voxels, which take 4294967316 bytes with the header, but the file has 28 bytes"
              $<TARGET_FILE:rimu> ${loaders_dir}/bad_short_grid.json -o ${loaders_exr} -q)
rimu_cli_test("loaders: a chain of 9 named spectra renders" 0 "discarded samples: 0 NaN"
              $<TARGET_FILE:rimu> ${loaders_dir}/named_spectra_chain.json -o ${CMAKE_CURRENT_BINARY_DIR}/cli_loaders_chain.exr --spp 1)
rimu_cli_test("loaders: IES flux overflow" 1 "bad_overflow.ies:8: the candela values are too large"
              $<TARGET_FILE:rimu-light> inspect ${loaders_dir}/bad_overflow.ies)
rimu_cli_test("loaders: rimu-light names the light file of a bad spectrum" 1 "bad_light_spectrum.json: /spectrum/blackbody"
              $<TARGET_FILE:rimu-light> inspect ${loaders_dir}/bad_light_spectrum.json)
rimu_cli_test("loaders: rimu-colour names the file of a spectrum without visible power" 1
              "infrared.csv: the spectrum .*has no power in 360-830 nm"
              $<TARGET_FILE:rimu-colour> report --csv ${loaders_dir}/infrared.csv)
rimu_cli_test("loaders: CSV with semicolons" 1 "semicolons.csv:1: cells are separated by semicolons; expected .*wavelength_nm,value.*nanometres"
              $<TARGET_FILE:rimu-colour> report --csv ${loaders_dir}/semicolons.csv)

# 100 000 nested arrays where a number is expected: the error message's dump overflowed the stack.
string(REPEAT "[" 100000 loaders_open)
string(REPEAT "]" 100000 loaders_close)
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/cli_loaders_deep.json
     "{\n \"camera\": {\"from\": ${loaders_open}0${loaders_close}, \"to\": [0, 0, 0]}\n}\n")
rimu_cli_test("loaders: 100000-deep JSON" 1 "cli_loaders_deep.json:2: arrays and objects are nested more than 256 deep"
              $<TARGET_FILE:rimu> ${CMAKE_CURRENT_BINARY_DIR}/cli_loaders_deep.json -o ${loaders_exr} -q)
