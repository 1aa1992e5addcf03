# The tools' command-line contract (tools/common/tool_main.h): exit 0 ok, 1 bad input (a bad option, an unknown
# subcommand, a value out of range), 2 a failure of the machine (a write that did not arrive); --help and --version
# exit 0 without data; no NaN or infinity is ever printed; every README command runs as written.
set(cli_check ${CMAKE_CURRENT_SOURCE_DIR}/cli/expect.sh)
set(cli_data ${CMAKE_CURRENT_SOURCE_DIR}/cli)
set(cli_out ${CMAKE_CURRENT_BINARY_DIR}/cli_contract)
file(MAKE_DIRECTORY ${cli_out})
# An abbreviated hash when built from a git checkout (cmake/GitCommit.cmake), else "unknown".
if(RIMU_GIT_COMMIT STREQUAL "unknown")
  set(cli_commit "commit unknown")
else()
  set(cli_commit "commit ${RIMU_GIT_COMMIT}")
endif()

foreach(tool rimu rimu-light rimu-colour rimu-upsample-table)
  rimu_cli_test("${tool} --help" 0 "Usage:" $<TARGET_FILE:${tool}> --help)
  rimu_cli_test("${tool} --version" 0 "^${tool} [0-9]+\\.[0-9]+\\.[0-9]+ \\(${cli_commit}\\)$" $<TARGET_FILE:${tool}> --version)
  rimu_cli_test("${tool} unknown option" 1 "^${tool}: " $<TARGET_FILE:${tool}> --no-such-option)
  # Help and version need no data: they work with RIMU_DATA pointing nowhere (rimu-light loaded its data first once).
  rimu_cli_test("${tool} --help without data" 0 "Usage:"
                ${CMAKE_COMMAND} -E env RIMU_DATA=/nonexistent $<TARGET_FILE:${tool}> --help)
  # Help text that cannot be written is an error, not a silent success.
  add_test(NAME "cli: ${tool} --help to a full disk"
           COMMAND sh -c "\"$0\" --help > /dev/full; test $? -eq 2" $<TARGET_FILE:${tool}>)
endforeach()
rimu_cli_test("rimu-light unknown subcommand" 1 "rimu-light: .*recolour" $<TARGET_FILE:rimu-light> recolour lamp.json)
rimu_cli_test("rimu-colour unknown subcommand" 1 "rimu-colour: .*analyse" $<TARGET_FILE:rimu-colour> analyse D65)
rimu_cli_test("rimu-light value CLI11 cannot parse" 1 "--lumens" $<TARGET_FILE:rimu-light> --type point --lumens lots)
rimu_cli_test("rimu-light missing value" 1 "--cone" $<TARGET_FILE:rimu-light> --type spot --lumens 5 --cone)
rimu_cli_test("rimu-light missing data is a message, not an abort" 1 "RIMU_DATA|/nonexistent"
              ${CMAKE_COMMAND} -E env RIMU_DATA=/nonexistent $<TARGET_FILE:rimu-light> convert --from "1 lm" --to cd)
rimu_cli_test("rimu unknown option named" 1 "rimu: .*--no-such-option" $<TARGET_FILE:rimu> --no-such-option)
rimu_cli_test("rimu-light unknown option named" 1 "rimu-light: .*--no-such-option" $<TARGET_FILE:rimu-light> --no-such-option)
rimu_cli_test("rimu-colour unknown option named" 1 "rimu-colour: .*--no-such-option"
              $<TARGET_FILE:rimu-colour> --no-such-option)
rimu_cli_test("rimu-colour no subcommand" 1 "rimu-colour: give a subcommand" $<TARGET_FILE:rimu-colour>)
rimu_cli_test("rimu-upsample-table unknown option named" 1 "rimu-upsample-table: .*--no-such-option"
              $<TARGET_FILE:rimu-upsample-table> --data ${CMAKE_SOURCE_DIR}/data --out ${cli_out} --no-such-option)
rimu_cli_test("rimu-upsample-table missing --out" 1 "--out" $<TARGET_FILE:rimu-upsample-table> --data ${CMAKE_SOURCE_DIR}/data)

# Write errors: a full disk (/dev/full) on standard output or a file output exits 2 and says so.
rimu_cli_test("rimu-light definition to a full disk" 2 "/dev/full.*No space"
              $<TARGET_FILE:rimu-light> --type point --lumens 800 -o /dev/full)
add_test(NAME "cli: rimu-light definition to a full standard output"
         COMMAND sh -c "\"$0\" --type point --lumens 800 > /dev/full; test $? -eq 2" $<TARGET_FILE:rimu-light>)
rimu_cli_test("rimu-light recolor to a full disk" 2 "/dev/full"
              $<TARGET_FILE:rimu-light> recolor ${cli_data}/spot_2700k.json --cct 4000 -o /dev/full)
add_test(NAME "cli: rimu-colour report to a full standard output"
         COMMAND sh -c "\"$0\" report D65 > /dev/full 2>\"$1\"; test $? -eq 2 && grep -q 'standard output' \"$1\""
                 $<TARGET_FILE:rimu-colour> ${cli_out}/report_full.log)
add_test(NAME "cli: rimu-light inspect to a full standard output"
         COMMAND sh -c "\"$0\" inspect \"$1\" > /dev/full; test $? -eq 2" $<TARGET_FILE:rimu-light>
                 ${cli_data}/spot_2700k.json)
rimu_cli_test("rimu-colour gamut CSV to a full disk" 2 "/dev/full"
              $<TARGET_FILE:rimu-colour> gamut --out ${cli_out}/gamut_full.png --csv /dev/full)
# An image to a full device is never a silent success: 2 (the write failed) or, should the format be chosen from the
# extension, 1 (no extension); either way the message names the path.
foreach(case "exr;-o;/dev/full" "png;-o;${cli_out}/full_disk.exr;--png;/dev/full")
  list(GET case 0 name)
  list(SUBLIST case 1 -1 outputs)
  add_test(NAME "cli: rimu ${name} to a full disk"
           COMMAND sh -c "log=$1; shift; \"$0\" --spp 1 --resolution 8x8 -q \"$@\" 2>\"$log\"; code=$?; \
                          cat \"$log\"; [ $code -eq 1 -o $code -eq 2 ] && grep -q /dev/full \"$log\""
                   $<TARGET_FILE:rimu> ${cli_out}/full_disk_${name}.log ${outputs})
endforeach()
rimu_cli_test("rimu-light output in a missing folder" 1 "no_such_folder.*does not exist"
              $<TARGET_FILE:rimu-light> --type point --lumens 800 -o ${cli_out}/no_such_folder/l.json)
rimu_cli_test("rimu-light plot path checked before the definition is written" 1 "no_such_folder.*does not exist"
              $<TARGET_FILE:rimu-light> --type point --lumens 800 -o ${cli_out}/never.json
              --plot ${cli_out}/no_such_folder/x.png)

# Values that would print NaN or infinity, or write an unreadable light, are refused at their option.
rimu_cli_test("rimu-light inspect distance 0" 1 "--distance: expected a distance"
              $<TARGET_FILE:rimu-light> inspect ${cli_data}/spot_2700k.json --distance 0)
rimu_cli_test("rimu-light inspect distance nan" 1 "--distance: expected a distance"
              $<TARGET_FILE:rimu-light> inspect ${cli_data}/spot_2700k.json --distance nan)
rimu_cli_test("rimu-light inspect angle nan" 1 "--angle: expected an angle"
              $<TARGET_FILE:rimu-light> inspect ${cli_data}/spot_2700k.json --angle nan)
rimu_cli_test("rimu-light inspect electrical watts 0" 1 "--electrical-watts: expected"
              $<TARGET_FILE:rimu-light> inspect ${cli_data}/spot_2700k.json --electrical-watts 0)
rimu_cli_test("rimu-light inspect IES distance 0" 1 "--distance: expected a distance"
              $<TARGET_FILE:rimu-light> inspect ${cli_data}/downlight.ies --distance 0)
rimu_cli_test("rimu-light convert area 1e-308" 1 "--area: the emitting area must be in"
              $<TARGET_FILE:rimu-light> convert --from "1000 lm" --to nt --type area --area 1e-308)
rimu_cli_test("rimu-light convert 1e30 EV" 1 "--from: an exposure value must be in \\[-50, 50\\]"
              $<TARGET_FILE:rimu-light> convert --from "1e30 EV" --to nt --type environment)
rimu_cli_test("rimu-light lumens inf" 1 "--lumens: a light's amount must be in"
              $<TARGET_FILE:rimu-light> --type point --lumens inf)
rimu_cli_test("rimu-light lumens 1e308" 1 "--lumens: a light's amount must be in"
              $<TARGET_FILE:rimu-light> --type point --lumens 1e308)
rimu_cli_test("rimu-light ev -1e308" 1 "--ev: an exposure value must be in"
              $<TARGET_FILE:rimu-light> --type distant --ev -1e308)
rimu_cli_test("rimu-light cone 1e-300" 1 "--cone: the cone angle must be in"
              $<TARGET_FILE:rimu-light> --type spot --lumens 800 --cone 1e-300)
rimu_cli_test("rimu-colour upsample 1e308 emission" 1 "rgb: expected three finite components"
              $<TARGET_FILE:rimu-colour> upsample 1e308 0 0 --emission)
rimu_cli_test("rimu-colour upsample nan" 1 "rgb: expected three finite components"
              $<TARGET_FILE:rimu-colour> upsample nan 0 0)

# rimu-light's first-hour fixes: 2700K as rimu takes it, area only where it works, --json, printed assumptions.
rimu_cli_test("rimu-light cct with K" 0 "\"blackbody\": 2700"
              $<TARGET_FILE:rimu-light> --type point --lumens 800 --cct 2700K)
rimu_cli_test("rimu-light area is not offered for a definition" 1 "convert --type area"
              $<TARGET_FILE:rimu-light> --type area --lumens 800)
rimu_cli_test("rimu-light convert states its assumptions" 0 "assuming a point light \\(--type\\)"
              $<TARGET_FILE:rimu-light> convert --from "1600 lm" --to cd)
rimu_cli_test("rimu-light convert states the assumed spectrum" 0 "assuming the spectrum of illuminant E"
              $<TARGET_FILE:rimu-light> convert --from "1600 lm" --to W --type point)
rimu_cli_test("rimu-light inspect --json" 0 "\"luminous_power_lm\": 800"
              $<TARGET_FILE:rimu-light> inspect ${cli_data}/spot_2700k.json --json)
rimu_cli_test("rimu-light inspect IES --json" 0 "\"total_luminous_flux_lm\": 1890\\.8"
              $<TARGET_FILE:rimu-light> inspect ${cli_data}/downlight.ies --json)

# A new user's first hour: every build/bin command in README.md, in order, from a scratch copy of the repository.
# About a minute in Release on two cores; the sanitizer build is several times slower, hence the generous timeout.
add_test(NAME "cli: README commands run as written"
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/readme_commands.sh ${CMAKE_SOURCE_DIR} ${CMAKE_BINARY_DIR})
set_tests_properties("cli: README commands run as written" PROPERTIES TIMEOUT 3600)

# A spectrum error names where the spectrum came from: the option that gave it, or the definition file.
rimu_cli_test("rimu-light spectrum error names the option" 1 "rimu-light: --illuminant: unknown illuminant 'D66'"
              $<TARGET_FILE:rimu-light> --type point --lumens 800 --illuminant D66)
rimu_cli_test("rimu-light convert spectrum error names the option" 1 "rimu-light: --illuminant: unknown illuminant"
              $<TARGET_FILE:rimu-light> convert --from "800 lm" --to W --illuminant D66)
rimu_cli_test("rimu-light spectrum error names the file" 1
              "rimu-light: [^ ]*bad_illuminant_light.json: /spectrum/illuminant: unknown illuminant 'D66'"
              $<TARGET_FILE:rimu-light> inspect ${cli_data}/bad_illuminant_light.json)
# Values beyond the accepted range of spectral values (0, or 1e-30 to 1e30) are refused at their line, before any
# integral is taken.
rimu_cli_test("rimu-light CSV whose integral overflows" 1 "overflowing_values.csv:2: .*1e\\+300 is larger in magnitude"
              $<TARGET_FILE:rimu-light> inspect ${cli_data}/overflowing_values.csv)
