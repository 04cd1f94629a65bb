# Writes version.cpp with the current git revision. Run at every build (target fsi_version), so
# the programs' --version and run.json name the commit they were built from, not the one CMake was
# configured at. configure_file rewrites the file only when its content changes, so an unchanged
# revision recompiles nothing.
#   cmake -DSOURCE_DIR=... -DTEMPLATE=... -DOUTPUT=... -DPROJECT_VERSION=... -P WriteVersion.cmake
set(FSI_GIT_REVISION "unknown")
find_package(Git QUIET)
if(GIT_FOUND)
  execute_process(COMMAND ${GIT_EXECUTABLE} describe --always --dirty --abbrev=12
    WORKING_DIRECTORY ${SOURCE_DIR} OUTPUT_VARIABLE _rev
    OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE _rc)
  if(_rc EQUAL 0 AND _rev)
    set(FSI_GIT_REVISION "${_rev}")
  endif()
endif()
configure_file(${TEMPLATE} ${OUTPUT} @ONLY)
