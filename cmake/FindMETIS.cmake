# FindMETIS: the METIS graph partitioner (Debian ships no CMake config for it).
# Provides the imported target METIS::METIS. Debian's METIS uses 32-bit idx_t.
find_path(METIS_INCLUDE_DIR metis.h)
find_library(METIS_LIBRARY metis)

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(METIS
  REQUIRED_VARS METIS_LIBRARY METIS_INCLUDE_DIR
  FAIL_MESSAGE "METIS not found: install the Debian package libmetis-dev (scripts/setup.sh)")

if(METIS_FOUND AND NOT TARGET METIS::METIS)
  add_library(METIS::METIS UNKNOWN IMPORTED)
  set_target_properties(METIS::METIS PROPERTIES
    IMPORTED_LOCATION "${METIS_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${METIS_INCLUDE_DIR}")
endif()
mark_as_advanced(METIS_INCLUDE_DIR METIS_LIBRARY)
