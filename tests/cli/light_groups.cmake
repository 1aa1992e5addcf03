# Light groups from the command line (docs/rendering.md, "Light groups"; the doctest side is
# tests/render/light_groups_test.cpp): the shipped example rebalanced by `rimu display --group`, the docs' commands,
# and the errors of the options and the scene key.
add_test(NAME "cli: light groups rendered, rebalanced and white-balanced by rimu display"
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/light_groups.sh $<TARGET_FILE:rimu> ${CMAKE_BINARY_DIR}/cli_light_groups
                 ${PROJECT_SOURCE_DIR})
rimu_cli_test("rimu bad light group name" 1 "bad_light_group.json: /lights/0/light_group: a light group's name may hold only"
              $<TARGET_FILE:rimu> ${CMAKE_CURRENT_SOURCE_DIR}/cli/bad_light_group.json -o ${CMAKE_BINARY_DIR}/cli_never_written.exr -q)
