# FindCHOLMOD: SuiteSparse's CHOLMOD (Debian ships no CMake config for it).
# Provides the imported target CHOLMOD::CHOLMOD and CHOLMOD_INCLUDE_DIR (the dir holding cholmod.h, as
# Eigen's CholmodSupport includes <cholmod.h>).
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
find_library(CHOLMOD_LIBRARY cholmod)
find_library(SUITESPARSE_CONFIG_LIBRARY suitesparseconfig)
foreach(_lib amd camd colamd ccolamd)
  string(TOUPPER ${_lib} _up)
  find_library(${_up}_LIBRARY ${_lib})
endforeach()

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(CHOLMOD
  REQUIRED_VARS CHOLMOD_LIBRARY CHOLMOD_INCLUDE_DIR SUITESPARSE_CONFIG_LIBRARY
  FAIL_MESSAGE "CHOLMOD not found: install the Debian package libsuitesparse-dev (scripts/setup.sh)")

if(CHOLMOD_FOUND AND NOT TARGET CHOLMOD::CHOLMOD)
  add_library(CHOLMOD::CHOLMOD UNKNOWN IMPORTED)
  set(_deps ${SUITESPARSE_CONFIG_LIBRARY})
  foreach(_lib AMD CAMD COLAMD CCOLAMD)
    if(${_lib}_LIBRARY)
      list(APPEND _deps ${${_lib}_LIBRARY})
    endif()
  endforeach()
  set_target_properties(CHOLMOD::CHOLMOD PROPERTIES
    IMPORTED_LOCATION "${CHOLMOD_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${_deps}")
endif()
mark_as_advanced(CHOLMOD_INCLUDE_DIR CHOLMOD_LIBRARY SUITESPARSE_CONFIG_LIBRARY)
