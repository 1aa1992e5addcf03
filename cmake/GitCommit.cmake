# The git commit the binaries are built from, for `--version` (spectral/version.h). Read at configure time; the
# configuration depends on the repository's HEAD log, so a new commit or checkout reconfigures and the commit
# stays current. A tree without git (a tarball) says "unknown".
set(RIMU_GIT_COMMIT "unknown")
find_package(Git QUIET)
if(GIT_FOUND)
  execute_process(COMMAND ${GIT_EXECUTABLE} rev-parse --short=12 HEAD
                  WORKING_DIRECTORY ${CMAKE_SOURCE_DIR} OUTPUT_VARIABLE rimu_git_head
                  RESULT_VARIABLE rimu_git_result OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(rimu_git_result EQUAL 0 AND rimu_git_head MATCHES "^[0-9a-f]+$")
    set(RIMU_GIT_COMMIT ${rimu_git_head})
    execute_process(COMMAND ${GIT_EXECUTABLE} rev-parse --absolute-git-dir
                    WORKING_DIRECTORY ${CMAKE_SOURCE_DIR} OUTPUT_VARIABLE rimu_git_dir
                    OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
    foreach(watched HEAD logs/HEAD)
      if(EXISTS "${rimu_git_dir}/${watched}")
        set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${rimu_git_dir}/${watched}")
      endif()
    endforeach()
  endif()
endif()
