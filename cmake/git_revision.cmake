# SIMBOB_GIT_REVISION: the source's `git describe --always --dirty` at configure time, for
# `simbob --version`. "unknown" when the source is not a git checkout of its own (a release
# tarball, or a tarball unpacked inside some other repository) or git is missing. A packager
# may set it: -DSIMBOB_GIT_REVISION=... . Only cmd/simbob's generated version.cpp holds it, so
# a new revision recompiles one small file and leaves every other object (and ccache) alone.
if(NOT DEFINED SIMBOB_GIT_REVISION)
  set(SIMBOB_GIT_REVISION "unknown")
  find_package(Git QUIET)
  if(GIT_FOUND)
    execute_process(COMMAND ${GIT_EXECUTABLE} rev-parse --show-toplevel
                    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
                    OUTPUT_VARIABLE _simbob_git_top OUTPUT_STRIP_TRAILING_WHITESPACE
                    RESULT_VARIABLE _simbob_git_status ERROR_QUIET)
    if(_simbob_git_status EQUAL 0)
      get_filename_component(_simbob_git_top "${_simbob_git_top}" REALPATH)
      get_filename_component(_simbob_src "${PROJECT_SOURCE_DIR}" REALPATH)
    endif()
    if(_simbob_git_status EQUAL 0 AND _simbob_git_top STREQUAL _simbob_src)
      execute_process(COMMAND ${GIT_EXECUTABLE} describe --always --dirty
                      WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
                      OUTPUT_VARIABLE _simbob_describe OUTPUT_STRIP_TRAILING_WHITESPACE
                      RESULT_VARIABLE _simbob_git_status ERROR_QUIET)
      if(_simbob_git_status EQUAL 0 AND NOT _simbob_describe STREQUAL "")
        set(SIMBOB_GIT_REVISION "${_simbob_describe}")
      endif()
    endif()
  endif()
endif()
message(STATUS "simbob ${PROJECT_VERSION}, git revision ${SIMBOB_GIT_REVISION}")
configure_file(${PROJECT_SOURCE_DIR}/cmd/simbob/version.cpp.in ${PROJECT_BINARY_DIR}/generated/version.cpp @ONLY)
