# FindLIGGGHTS: Debian ships LIGGGHTS 3.8 as libliggghts-dev without a CMake config.
#
# Result: the imported target LIGGGHTS::LIGGGHTS (library, headers as SYSTEM, MPI), and
# LIGGGHTS_FOUND, LIGGGHTS_INCLUDE_DIR, LIGGGHTS_LIBRARY, LIGGGHTS_VERSION.
find_path(LIGGGHTS_INCLUDE_DIR NAMES lammps.h PATH_SUFFIXES liggghts
  DOC "Directory holding LIGGGHTS' lammps.h (Debian: /usr/include/liggghts)")
find_library(LIGGGHTS_LIBRARY NAMES liggghts DOC "LIGGGHTS shared library")

if(LIGGGHTS_LIBRARY)
  # The soname carries the version: libliggghts.so.3.8.0
  file(REAL_PATH "${LIGGGHTS_LIBRARY}" _liggghts_real)
  if(_liggghts_real MATCHES "\\.so\\.([0-9]+\\.[0-9]+(\\.[0-9]+)?)$")
    set(LIGGGHTS_VERSION "${CMAKE_MATCH_1}")
  endif()
endif()

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(LIGGGHTS
  REQUIRED_VARS LIGGGHTS_LIBRARY LIGGGHTS_INCLUDE_DIR
  VERSION_VAR LIGGGHTS_VERSION
  REASON_FAILURE_MESSAGE "Install Debian's libliggghts-dev (scripts/install-deps does this).")

if(LIGGGHTS_FOUND AND NOT TARGET LIGGGHTS::LIGGGHTS)
  add_library(LIGGGHTS::LIGGGHTS SHARED IMPORTED)
  set_target_properties(LIGGGHTS::LIGGGHTS PROPERTIES
    IMPORTED_LOCATION "${LIGGGHTS_LIBRARY}")
  # SYSTEM: LIGGGHTS' headers are not ours and must not trip our -Werror.
  target_include_directories(LIGGGHTS::LIGGGHTS SYSTEM INTERFACE "${LIGGGHTS_INCLUDE_DIR}")
  target_link_libraries(LIGGGHTS::LIGGGHTS INTERFACE MPI::MPI_CXX)
endif()
mark_as_advanced(LIGGGHTS_INCLUDE_DIR LIGGGHTS_LIBRARY)
