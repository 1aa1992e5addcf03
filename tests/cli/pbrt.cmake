# pbrt-v4 scenes (docs/pbrt-import.md): bad input exits 1 with file:line and writes nothing; --strict; the report of
# what is ignored; rimu-convert's JSON renders from its own folder.
add_test(NAME "cli: pbrt scenes through rimu and rimu-convert"
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/pbrt.sh $<TARGET_FILE:rimu> $<TARGET_FILE:rimu-convert>
                 ${CMAKE_CURRENT_SOURCE_DIR}/data/pbrt ${CMAKE_CURRENT_BINARY_DIR}/cli_pbrt)
rimu_cli_test("rimu pbrt unknown statement" 1 "bad_unknown_statement.pbrt:4: unknown statement 'Shpe'"
              $<TARGET_FILE:rimu> ${CMAKE_CURRENT_SOURCE_DIR}/data/pbrt/bad_unknown_statement.pbrt -o ${CMAKE_CURRENT_BINARY_DIR}/cli_never_written.exr -q)
rimu_cli_test("rimu-convert usage" 0 "pbrt-v4" $<TARGET_FILE:rimu-convert> --help)
add_test(NAME "cli: hostile pbrt inputs: non-regular top-level files, include and instance bombs, Latin-1, unclosed ObjectBegin"
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/pbrt_hostile.sh $<TARGET_FILE:rimu> $<TARGET_FILE:rimu-convert>
                 ${CMAKE_CURRENT_BINARY_DIR}/cli_pbrt_hostile)
add_test(NAME "cli: the scene hash covers what a pbrt scene reads: sub-folder includes, single quotes, any extension"
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/pbrt_scene_hash.sh $<TARGET_FILE:rimu>
                 ${CMAKE_CURRENT_BINARY_DIR}/cli_pbrt_scene_hash)
