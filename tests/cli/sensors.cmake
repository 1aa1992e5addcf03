# Sensors (docs/scene-format.md, "sensors"): measured after the image or alone, their files, and bad input.
set(sensors_scene ${CMAKE_CURRENT_SOURCE_DIR}/cli/sensors_lamp.json)
rimu_cli_test("rimu sensors after the image" 0
              "wrote .*cli_sensors\\.sensors\\.csv, .*cli_sensors\\.sensors\\.json, .*cli_sensors\\.sensors\\.floor\\.png"
              $<TARGET_FILE:rimu> ${sensors_scene} -o ${CMAKE_BINARY_DIR}/cli_sensors.exr)
rimu_cli_test("rimu sensors summary" 0
              "sensor floor \\(3x3\\): Emin [0-9.]+ lx, Eavg [0-9.]+ lx, Emax [0-9.]+ lx, U0 0\\.[0-9]+"
              $<TARGET_FILE:rimu> ${sensors_scene} -o ${CMAKE_BINARY_DIR}/cli_sensors_summary.exr)
# 1000 cd at 2 m: 250 lx straight below, plus what the grey floor sends back (nothing: the meter faces up from it).
rimu_cli_test("rimu --sensors-only reads 250 lx below a 1000 cd lamp at 2 m" 0 "sensor below: 2[45][0-9]\\.[0-9]+ lx"
              $<TARGET_FILE:rimu> ${sensors_scene} --sensors-only --sensor-samples 256
              --sensors-out ${CMAKE_BINARY_DIR}/cli_sensors_only)
rimu_cli_test("rimu --sensors-only without sensors" 1 "--sensors-only.*no \"sensors\""
              $<TARGET_FILE:rimu> --sensors-only -o ${CMAKE_BINARY_DIR}/cli_never_written.exr)
rimu_cli_test("rimu grid without counts or spacing" 1 "bad_sensors.json: /sensors/grids/0: give either \"counts\""
              $<TARGET_FILE:rimu> ${CMAKE_CURRENT_SOURCE_DIR}/cli/bad_sensors.json -o ${CMAKE_BINARY_DIR}/cli_never_written.exr)
rimu_cli_test("rimu --sensor-samples out of range" 1 "--sensor-samples"
              $<TARGET_FILE:rimu> ${sensors_scene} --sensor-samples 0 -o ${CMAKE_BINARY_DIR}/cli_never_written.exr)
rimu_cli_test("rimu --sensors-out into a missing folder" 1 "no_such_folder"
              $<TARGET_FILE:rimu> ${sensors_scene} --sensors-only --sensors-out ${CMAKE_BINARY_DIR}/no_such_folder/x)
# The example of docs/scene-format.md ("Cylindrical and semi-cylindrical illuminance", "Scotopic and melanopic
# quantities"): every meter kind with scotopic and melanopic readings, at fewer samples than the scene asks.
rimu_cli_test("rimu cylindrical meters with scotopic and melanopic EDI" 0
              "sensor face_towards_lamp: [0-9.]+ lx ± [0-9.]+ lx \\(standard error\\); scotopic [0-9.]+ lx ± [0-9.]+; melanopic EDI [0-9.]+ lx"
              $<TARGET_FILE:rimu> ${CMAKE_SOURCE_DIR}/data/scenes/examples/pedestrian_meters.json --sensors-only
              --sensor-samples 64 -o ${CMAKE_BINARY_DIR}/cli_pedestrian.exr)
