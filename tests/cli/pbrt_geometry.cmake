# pbrt-v4 geometry (docs/pbrt-import.md, Shapes): a damaged .ply.gz exits 1 naming the file and what is wrong, and
# writes no image.
set(pbrt_geometry_data ${CMAKE_CURRENT_SOURCE_DIR}/data/pbrt)
set(pbrt_geometry_never ${CMAKE_CURRENT_BINARY_DIR}/cli_pbrt_geometry_never_written.exr)
rimu_cli_test("rimu pbrt truncated ply.gz" 1 "truncated.ply.gz.*truncated"
              $<TARGET_FILE:rimu> ${pbrt_geometry_data}/bad_truncated_gz.pbrt -o ${pbrt_geometry_never} -q)
rimu_cli_test("rimu pbrt corrupt ply.gz" 1 "corrupt.ply.gz.*corrupt"
              $<TARGET_FILE:rimu> ${pbrt_geometry_data}/bad_corrupt_gz.pbrt -o ${pbrt_geometry_never} -q)
